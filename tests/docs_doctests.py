"""Runs every Python snippet of the documentation as a doctest, so the docs cannot drift.

A snippet is a ```pycon block of README.md or docs/**/*.md; a page's blocks run in order with
shared names, in the current directory, outputs compared with ELLIPSIS and NORMALIZE_WHITESPACE.
Usage: PYTHONPATH=build/python docs_doctests.py REPO
"""
import doctest
import pathlib
import re
import sys

repo = pathlib.Path(sys.argv[1]).resolve()
parser = doctest.DocTestParser()
runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
pages = 0
for page in [repo / "README.md", *sorted((repo / "docs").rglob("*.md"))]:
    blocks = re.findall(r"```pycon\n(.*?)```", page.read_text(), re.S)
    if not blocks:
        continue
    pages += 1
    names = {}
    for number, block in enumerate(blocks, 1):
        test = parser.get_doctest(block, names, f"{page.relative_to(repo)} block {number}", str(page), 0)
        runner.run(test, clear_globs=False)
        names = test.globs  # the next block sees this one's names
results = runner.summarize(verbose=False)
print(f"{results.attempted} examples in {pages} pages, {results.failed} failed")
sys.exit(1 if results.failed or not results.attempted else 0)
