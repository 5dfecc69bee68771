"""Compile C and Fortran sources into a shared library, once, cached by content.

One job: sources (files on disk or generated text) -> a `.so` that cffi can
dlopen. The library's name carries a SHA-256 of everything that decides the
machine code (the compiler's version line, the flags, every source's name and
bytes, the include files, the user's own files a source includes), so an unchanged
source is never compiled twice and an edited one always is. Libraries live in a cache folder:

    $WASHER_CACHE, else $XDG_CACHE_HOME/washer/compiled, else ~/.cache/washer/compiled

Compilers are the system's `gcc` and `gfortran` (Debian packages `gcc` and
`gfortran`); $CC and $FC override them. A failed compile raises CompileError
with the compiler's own messages, which name the user's file and line.

Used by the AUTO user files (washer.cont.user_problem.user_files_native) and by generated problems.
"""
from __future__ import annotations

import hashlib
import importlib.util
import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

#: Bumped when the way libraries are built changes (invalidates the cache).
BUILD_VERSION = "1"
#: Optimisation as AUTO-07p's own build of user files (-O), plus position-independent code.
C_FLAGS = ("-O2", "-fPIC")
FORTRAN_FLAGS = ("-O2", "-fPIC")
FORTRAN_SUFFIXES = (".f90", ".f", ".f95", ".f03", ".F", ".F90")


class CompileError(RuntimeError):
    """A source did not compile or link; the message holds the compiler's output."""


@dataclass(frozen=True)
class Source:
    """One translation unit: `name` is how messages and the compiler call it
    (a path for user files), `text` its bytes (None: read `path`)."""
    name: str
    text: bytes | None = None
    path: Path | None = None

    def data(self) -> bytes:
        if self.text is not None:
            return self.text
        try:
            return Path(self.path).read_bytes()
        except OSError as exc:
            raise CompileError(f"{self.path}: cannot read the source ({exc.strerror})") from None

    @property
    def fortran(self) -> bool:
        return Path(self.name).suffix in FORTRAN_SUFFIXES


def source_file(path) -> Source:
    """A source on disk (compiled where it is, so messages name its path)."""
    p = Path(path)
    return Source(name=str(p), path=p)


#: A line that includes another file of the user's: Fortran's INCLUDE 'NAME' (any case,
#: fixed or free form) and the preprocessor's #include "NAME" (not <NAME>: the system's).
_INCLUDE_LINE = re.compile(rb"""^[ \t]*(?:#[ \t]*include[ \t]*"([^"\n]+)"|include[ \t]*['"]([^'"\n]+)['"])""",
                           re.IGNORECASE | re.MULTILINE)


def included_files(path) -> list[Path]:
    """The files a source on disk includes from its own folder, as the compiler finds
    them (beside the including file), and the files those include, in order, each once.

    They decide the machine code as the source does (AUTO's brc.f takes its dimensions
    from brc.inc): a library keyed without them would outlive an edit of them."""
    found: list[Path] = []
    todo = [Path(path)]
    while todo:
        current = todo.pop(0)
        try:
            text = current.read_bytes()
        except OSError:
            continue
        for m in _INCLUDE_LINE.finditer(text):
            name = (m.group(1) or m.group(2)).decode(errors="replace").strip()
            inc = current.parent / name
            if inc.is_file() and inc not in found:
                found.append(inc)
                todo.append(inc)
    return found


def source_text(name: str, text: str | bytes) -> Source:
    """A generated source (written to the build folder under `name`)."""
    return Source(name=name, text=text.encode() if isinstance(text, str) else text)


def cache_dir() -> Path:
    """Where compiled libraries are cached: $WASHER_CACHE, else
    $XDG_CACHE_HOME/washer/compiled (default ~/.cache/washer/compiled)."""
    env = os.environ.get("WASHER_CACHE")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "washer" / "compiled"


#: (compiler, PATH) -> its path, of the compilers found (a search of PATH costs more
#: than a short run's set-up otherwise; a compiler not found is searched again).
_FOUND: dict = {}


def _compiler(kind: str) -> str:
    env, default, package = {"c": ("CC", "gcc", "gcc"),
                             "fortran": ("FC", "gfortran", "gfortran")}[kind]
    exe = os.environ.get(env) or default
    where = (exe, os.environ.get("PATH"))
    if where not in _FOUND:
        found = shutil.which(exe)
        if found is not None:
            _FOUND[where] = found
    if where not in _FOUND:
        raise CompileError(f"no {kind} compiler: '{exe}' is not on PATH (install the Debian "
                           f"package {package}: apt-get install {package}; or set ${env})")
    return exe


@lru_cache(maxsize=None)
def _version(exe: str) -> str:
    try:
        out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.SubprocessError) as exc:
        raise CompileError(f"cannot run the compiler '{exe}': {exc}") from None
    return (out.stdout.splitlines() or [""])[0]


#: library_key's results in this process by everything they hash (the headers by name, size
#: and modification time): every run of a traced or compiled user file asks for the key of
#: the same sources again, and the hash of its ~60 KB cost a short run 0.1-0.2 ms
_KEYS: dict = {}
_KEYS_MAX = 64


def _headers(folder) -> list[tuple[str, str]]:
    """(name, path) of the headers `*.h` in folder, by name: what Path(folder).glob('*.h')
    lists, sorted, read with os.scandir (pathlib's glob and Path objects cost a short run
    of a small problem more than its hash, once per library a run)."""
    try:
        with os.scandir(folder) as entries:
            return sorted((e.name, e.path) for e in entries if e.name.endswith(".h"))
    except (FileNotFoundError, NotADirectoryError, PermissionError):
        return []                       # (glob lists nothing there either)


def library_key(sources: list[Source], includes: list[Path] = (), extra: str = "") -> str:
    """The content hash naming a library: compilers' versions, flags, sources, includes."""
    kinds = {"fortran" if s.fortran else "c" for s in sources}
    kinds.add("c")
    versions = tuple(_version(_compiler(kind)) for kind in sorted(kinds))
    texts = tuple((Path(s.name).name, s.data()) for s in sources)
    texts += tuple((inc.name, inc.read_bytes()) for s in sources if s.path is not None
                   for inc in included_files(s.path))
    headers = [_headers(inc) for inc in includes]
    stamps = tuple((name, st.st_size, st.st_mtime_ns)
                   for files in headers for name, path in files for st in (os.stat(path),))
    memo = (versions, extra, texts, stamps)
    key = _KEYS.get(memo)
    if key is not None:
        return key
    h = hashlib.sha256()
    for version in versions:
        h.update(version.encode() + b"\0")
    h.update(repr((BUILD_VERSION, C_FLAGS, FORTRAN_FLAGS, extra)).encode())
    for name, data in texts:
        h.update(name.encode() + b"\0" + data + b"\0")
    for files in headers:
        for name, path in files:
            with open(path, "rb") as fh:
                h.update(name.encode() + b"\0" + fh.read() + b"\0")
    key = h.hexdigest()[:20]
    if len(_KEYS) >= _KEYS_MAX:
        _KEYS.clear()
    _KEYS[memo] = key
    return key


def build_library(sources: list[Source], name: str, includes: list[Path] = (),
                  defines: dict | None = None, cache: Path | None = None,
                  flags: tuple = ()) -> Path:
    """The shared library of `sources`, compiled now or found in the cache.

    name: a readable prefix of the library file; includes: header folders;
    defines: preprocessor macros for the C sources; flags: more options of the C
    compiler (after C_FLAGS). Compiling happens in a
    temporary folder (Fortran module files go there too, never beside the
    user's file) and the finished library is moved into place atomically, so
    concurrent builds of the same sources cannot leave half a file."""
    defines = dict(defines or {})
    key = library_key(sources, includes, repr(sorted(defines.items())) + (
        repr(tuple(flags)) if flags else ""))
    folder = Path(cache) if cache is not None else cache_dir()
    lib = folder / f"{_safe(name)}-{key}.so"
    if lib.exists():
        return lib
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CompileError(f"{folder}: cannot create the compile cache ({exc.strerror}); "
                           "set $WASHER_CACHE to a writable folder") from None
    fortran = any(s.fortran for s in sources)
    with tempfile.TemporaryDirectory(prefix="washer-build-") as tmp:
        objs = []
        for k, s in enumerate(sources):
            if s.path is not None:
                src = str(s.path)
            else:
                src = os.path.join(tmp, Path(s.name).name)
                Path(src).write_bytes(s.text)
            obj = os.path.join(tmp, f"{k}.o")
            if s.fortran:
                cmd = [_compiler("fortran"), *FORTRAN_FLAGS, "-J", tmp, "-c", src, "-o", obj]
            else:
                cmd = [_compiler("c"), *C_FLAGS, *flags, *(f"-I{i}" for i in includes),
                       *(f"-D{k}={v}" for k, v in defines.items()), "-c", src, "-o", obj]
            _call(cmd, s.name)
            objs.append(obj)
        out = os.path.join(tmp, "lib.so")
        linker = _compiler("fortran") if fortran else _compiler("c")
        _call([linker, "-shared", *objs, "-o", out, "-lm"], name)
        partial = folder / f".{lib.name}.{os.getpid()}"
        shutil.copyfile(out, partial)
        os.replace(partial, lib)
    return lib


def declarations(cdef: str, name: str):
    """cffi's FFI of the C declarations `cdef`, to dlopen libraries with (ABI mode).

    It is cffi's out-of-line ABI module of them (`set_source(module, None)`), written once
    into the cache folder, named by a hash of the declarations and cffi's version, and
    imported from there: parsing them (pycparser's import and its parse) at every start
    cost a short run about 150 M instructions, a third of numpy's import. Where the cache
    cannot be written, the declarations are parsed here (the same FFI, slower to make)."""
    # the version of cffi's backend, which the module is made for (cffi's own import
    # is not needed to load it)
    from _cffi_backend import __version__ as version
    key = hashlib.sha256(f"{version}\0{cdef}".encode()).hexdigest()[:20]
    module = f"_washer_ffi_{_safe(name)}_{key}"
    path = cache_dir() / f"{module}.py"
    if not path.exists():
        import cffi
        builder = cffi.FFI()
        builder.set_source(module, None)
        builder.cdef(cdef)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            # written whole under another name, then moved: a concurrent start never
            # imports half a file
            partial = path.with_name(f".{path.name}.{os.getpid()}")
            builder.emit_python_code(str(partial))
            os.replace(partial, path)
        except OSError:
            return builder
    spec = importlib.util.spec_from_file_location(module, path)
    loaded = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(loaded)
    return loaded.ffi


def _call(cmd: list[str], what: str) -> None:
    try:
        res = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    except (OSError, subprocess.SubprocessError) as exc:
        raise CompileError(f"{what}: cannot run {cmd[0]}: {exc}") from None
    if res.returncode != 0:
        msg = (res.stderr or res.stdout).strip()
        raise CompileError(f"{what}: compiling failed ({Path(cmd[0]).name} exit "
                           f"{res.returncode}):\n{msg}")


def _safe(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in name) or "lib"
