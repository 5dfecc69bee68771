"""Text input files read with errors that name them: the bytes of a constants file, a
b-/s-/d-file, a parameter file or a sweep spec decoded as UTF-8, a binary or non-UTF-8
file refused with its name, line and the bad byte (never read as partly empty)."""
from __future__ import annotations


def decode_text(data: bytes, source: str, what: str, error=ValueError) -> str:
    """UTF-8 text of a file's bytes, or `error` naming the file, line and the bad byte.

    AUTO's files are plain ASCII; a NUL byte or an undecodable byte means a
    binary or corrupt file, which must not be read as (partly) empty.
    """
    nul = data.find(b"\0")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        raise error(f"{source}:{line}: a NUL byte: this is a binary file, not {what}")
    try:
        return data.decode("utf-8-sig")          # an editor's BOM is not content
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise error(f"{source}:{line}: byte 0x{data[exc.start]:02x} is not UTF-8 text: "
                    f"expected {what} (plain text)") from None
