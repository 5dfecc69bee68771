"""The stamp that ties each compiled module to the C++ sources it was built from.

build.py compiles into washer._kernel and washer._cont a function that returns the
sha256 of the module's sources (`sources_hash`); where those sources sit beside the
package (a source checkout: csrc/ next to washer/), importing a module whose stamp is
not the current sources' hash raises ImportError (`check`) naming the module and the
command that rebuilds it: a module left over from older sources (after `git pull`
without `python build.py`) never runs in place of the current ones. An installed
wheel has no csrc/: its modules were built with it, and nothing is checked.

Standard library only: build.py loads this file by its path, before the package
can be imported (setuptools runs build.py in an isolated build environment).
"""
from __future__ import annotations

import hashlib
from pathlib import Path

#: The source checkout's root (the folder holding build.py, csrc/ and washer/).
ROOT = Path(__file__).resolve().parent.parent
#: What a module is compiled from: every file with these suffixes in its folder.
SUFFIXES = (".c", ".cpp", ".h", ".hpp")
#: module -> (its source folder under ROOT, sub-folders of it that belong to another module).
FOLDERS = {"washer._kernel": ("csrc", ("cont",)), "washer._cont": ("csrc/cont", ())}
#: module -> the compiled function returning its stamp (a NUL-terminated hex digest).
FUNCTIONS = {"washer._kernel": "washer_sources_sha256", "washer._cont": "cont_sources_sha256"}


def source_files(module: str, root: Path = ROOT) -> list[Path]:
    """The files `module` is built from, sorted by their path relative to root
    (posix form: the order does not depend on the file system or the platform)."""
    folder, others = FOLDERS[module]
    base = root / folder
    files = [p for p in base.rglob("*")
             if p.suffix in SUFFIXES and p.is_file()
             and p.relative_to(base).parts[0] not in others]
    return sorted(files, key=lambda p: p.relative_to(root).as_posix())


def sources_hash(module: str, root: Path = ROOT) -> str:
    """sha256 (hex) over `module`'s source files: for each, its relative path and its
    bytes, each preceded by its length (no two file sets hash alike by moving bytes
    between a name and a content)."""
    h = hashlib.sha256()
    for p in source_files(module, root):
        for part in (p.relative_to(root).as_posix().encode(), p.read_bytes()):
            h.update(len(part).to_bytes(8, "little"))
            h.update(part)
    return h.hexdigest()


def stamp_code(module: str, root: Path = ROOT) -> tuple[str, str]:
    """(cdef declaration, C++ definition) of `module`'s stamp function, returning the
    hash of the sources as they are now (build.py appends them to the module's cdef
    and set_source)."""
    name = FUNCTIONS[module]
    return (f"const char *{name}(void);",
            f'static const char *{name}(void) {{ return "{sources_hash(module, root)}"; }}')


def check(module: str, ffi, lib, root: Path = ROOT) -> None:
    """Raise ImportError unless `module` (its cffi `ffi` and `lib`) was built from the
    sources under root; nothing is checked where root has no sources (an installed
    wheel). A module built before the stamp existed carries none: it is stale too."""
    folder = root / FOLDERS[module][0]
    if not folder.is_dir():
        return
    fn = getattr(lib, FUNCTIONS[module], None)
    stamp = None if fn is None else ffi.string(fn()).decode()
    want = sources_hash(module, root)
    if stamp != want:
        only = " cont" if module == "washer._cont" else ""
        seen = f"its stamp {stamp[:12]}" if stamp else "it carries no stamp"
        raise ImportError(
            f"{module} was built from other sources than the ones in {folder} "
            f"({seen}, the sources' {want[:12]}): rebuild it "
            f"with `python build.py{only}` in {root} (or `pip install -e .`)")
