"""Runs every command-line snippet of the documentation, so the docs cannot drift from the tool.

A snippet is a line starting with "$ " inside a ```console block of README.md and docs/**/*.md. Each page's
snippets run in order in a fresh directory (with bench/ linked in, as from the repository root),
with the build's horizon, then the interpreter running this script, first on PATH; any non-zero exit fails the test. Snippets that need a
GPU (--backend cuda, --gpus) run only where the cuda backend is usable, those under mpirun only
where MPI was built, and those importing an optional Python package (meshio) only where it is. Also checks that the CLI reference names every flag the CLI has.

Usage: docs_snippets.py REPO BUILD WORKDIR
"""
import importlib.util
import os
import pathlib
import re
import shutil
import subprocess
import sys

repo, build, work = (pathlib.Path(p).resolve() for p in sys.argv[1:4])
cli = build / "bin" / "horizon"
env = dict(os.environ, PATH=f"{cli.parent}:{pathlib.Path(sys.executable).parent}:{os.environ['PATH']}", PYTHONPATH=str(build / "python"),
           OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")
gpu = subprocess.run([cli, "search", "lattice:2", "--horizon", "1", "--backend", "cuda", "--quiet"],
                     capture_output=True).returncode == 0
mpi = shutil.which("mpirun") is not None and "--exchange" in subprocess.run(
    [cli, "search", "--help"], capture_output=True, text=True).stdout


def snippets(page):
    """The "$ " lines of the page's console blocks."""
    blocks = re.findall(r"```console\n(.*?)```", page.read_text(), re.S)
    return [line[2:] for block in blocks for line in block.splitlines() if line.startswith("$ ")]


def missing_module(command):
    """The first module a `python3 -c` snippet imports that this interpreter lacks, or None."""
    for name in re.findall(r"\bimport (\w+)", command) if command.startswith("python3") else []:
        if importlib.util.find_spec(name) is None:
            return name
    return None


failures, ran, skipped = [], 0, 0
for page in [repo / "README.md", *sorted((repo / "docs").rglob("*.md"))]:
    commands = snippets(page)
    if not commands:
        continue
    directory = work / page.relative_to(repo).with_suffix("")
    shutil.rmtree(directory, ignore_errors=True)
    directory.mkdir(parents=True)
    (directory / "bench").symlink_to(repo / "bench")
    for command in commands:
        lacking = ("a GPU" if not gpu and re.search(r"--backend cuda|--gpus", command) else
                   "MPI" if not mpi and command.startswith("mpirun") else missing_module(command))
        if lacking:
            print(f"skipped (no {lacking} here): {page.name}: $ {command}")
            skipped += 1
            continue
        result = subprocess.run(command, shell=True, cwd=directory, env=env, capture_output=True, text=True)
        ran += 1
        if result.returncode != 0:
            failures.append(f"{page.relative_to(repo)}: $ {command}\n  exit {result.returncode}: {result.stderr.strip()[-800:]}")

# Every flag of every subcommand appears in the CLI reference.
reference = (repo / "docs" / "reference" / "cli.md").read_text()
for sub in ("generate", "search", "verify"):
    help_text = subprocess.run([cli, sub, "--help"], capture_output=True, text=True).stdout
    for flag in sorted(set(re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", help_text)) - {"--help"}):
        if f"`{flag}" not in reference and f" {flag}" not in reference:
            failures.append(f"docs/reference/cli.md does not describe `horizon {sub} {flag}`")

print(f"{ran} snippets ran, {skipped} skipped, {len(failures)} failures")
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
