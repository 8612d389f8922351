# Sphinx configuration of horizon's documentation site: `make docs` builds it into build/docs/html.
# The C++ API comes from the headers' /// comments (Doxygen XML, read by Breathe), the Python API
# from the package's docstrings (autodoc; the built module must be on PYTHONPATH).
import os
import re

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
with open(os.path.join(ROOT, "CMakeLists.txt")) as cmake:  # the one place the version is set
    release = version = re.search(r"project\(horizon VERSION ([0-9.]+)", cmake.read()).group(1)

project = "horizon"
author = "the horizon developers"
copyright = "2026, the horizon developers (BSD-3-Clause)"

extensions = ["myst_parser", "breathe", "sphinx.ext.autodoc", "sphinx.ext.napoleon"]
myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]

breathe_projects = {"horizon": os.environ.get("HORIZON_DOXYGEN_XML", os.path.join(ROOT, "build", "docs", "doxygen", "xml"))}
breathe_default_project = "horizon"
breathe_default_members = ("members",)
breathe_show_include = False  # every header is named in the table above
breathe_domain_by_extension = {"h": "c"}  # horizon.h and version.h are C

autodoc_member_order = "bysource"
autodoc_typehints = "none"

# Warnings are errors (-W) and internal references must resolve (-n); names from the standard
# library, NumPy, CUDA and MPI are outside this site.
nitpicky = True
nitpick_ignore_regex = [
    (r"cpp:.*", r"(std|hwy|MPI_\w+|CUstream_st|cudaStream_t)(::.*)?"),
    (r"cpp:.*", r"(size_t|int64_t|int32_t|uint64_t|uint32_t|uint8_t|ptrdiff_t|std::.*)"),
    (r"c:.*", r"(size_t|int64_t|int32_t|uint64_t)"),
    (r"py:.*", r"(numpy|np|scipy|optional|array-like|array_like|int|float|str|bool|callable)(\..*)?"),
]

html_theme = "furo"
html_title = f"horizon {release}"
html_static_path = []
