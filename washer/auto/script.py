"""AUTO scripts (NAME.auto) and the interactive prompt, in AUTO's dialect.

AUTO's CLUI runs its scripts as Python with its commands predefined and accepts
Python 2 `print` statements (`print "text"`, `print a, b`, `print x,`). They are
rewritten here into calls, token by token, keeping every line where it was, so
messages name the script's own line numbers. Before that, each line goes through AUTO's
shorthand (interactiveBindings.processShorthand): `! cmd` and `shell cmd` run cmd in the
shell, `ls`, `cd DIR`, `cat FILE` call those commands, and `rm`, `mkdir`, `rmdir`,
`clear`, `less` lines (and `cp`/`mv` ones that are not calls) go to the shell.
"""
from __future__ import annotations

import code
import io
import sys
import tokenize
import traceback
from pathlib import Path

from washer.auto import clui


class ScriptError(RuntimeError):
    """A script stopped: the message names the script, the line and the cause."""


#: AUTO's shorthand words (interactiveBindings.processShorthand).
SHORT_COMMANDS = ("ls", "cd", "cat")
SHORT_UNIX = ("clear", "less", "mkdir", "rmdir", "rm")
SHORT_DUPLICATES = ("cp", "mv")
#: Second words that make a line Python (an operator or keyword after a name).
PYTHON_WORDS = ("in", "is", "and", "or", "if", "else", "for", "not", "+=", "-=", "*=",
                "/=", "==", "!=", "<", ">", "<=", ">=", "+", "*", "/", "%", "**", "-")


def shorthand(line: str) -> str:
    """One script line with AUTO's shorthand made a call (see the module docstring);
    any other line unchanged. A word followed by '(' or an assignment stays Python."""
    words = line.split()
    if not words:
        return line
    indent = line[:len(line) - len(line.lstrip())]
    body = line.strip()
    if body.startswith("!"):
        return f"{indent}shell({body[1:].strip()!r})"
    if len(words) > 1 and (words[1][0] in "(=[,:" or words[1] in PYTHON_WORDS):
        return line                     # a call, an assignment, an expression: Python
    if words[0] == "shell" and len(words) > 1:
        return f"{indent}shell({body[5:].strip()!r})"
    if words[0] in SHORT_UNIX or (words[0] in SHORT_DUPLICATES and
                                  (len(words) != 2 or words[1].startswith("-"))):
        return f"{indent}shell({body!r})"
    if words[0] in SHORT_COMMANDS and len(words) <= 2:
        return f"{indent}{words[0]}({words[1]!r})" if len(words) == 2 else f"{indent}{words[0]}()"
    return line


def translate(source: str) -> str:
    """AUTO's shorthand lines -> calls; Python 2 print statements -> print() calls;
    everything else unchanged."""
    source = "".join(shorthand(ln[:len(ln.rstrip("\r\n"))]) + ln[len(ln.rstrip("\r\n")):]
                     for ln in source.splitlines(keepends=True))
    lines = source.splitlines(keepends=True)
    try:
        tokens = list(tokenize.generate_tokens(io.StringIO(source).readline))
    except (tokenize.TokenError, IndentationError, SyntaxError):
        return source
    edits = []                          # (row, col, text) insertions, applied from the end
    at_start = True
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if tok.type in (tokenize.NEWLINE, tokenize.NL, tokenize.INDENT, tokenize.DEDENT,
                        tokenize.COMMENT):
            if tok.type == tokenize.NEWLINE:
                at_start = True
            i += 1
            continue
        if at_start and tok.type == tokenize.NAME and tok.string == "print":
            nxt = tokens[i + 1] if i + 1 < len(tokens) else None
            bare = nxt is None or nxt.type in (tokenize.NEWLINE, tokenize.ENDMARKER,
                                               tokenize.COMMENT)
            if bare:
                edits.append((tok.end, tok.end, "()"))
            elif not (nxt.type == tokenize.OP and nxt.string in
                      ("(", "=", ".", "[", ",", ")")):
                # the statement's end: the NEWLINE token of this logical line
                j = i + 1
                last = None
                depth = 0
                while j < len(tokens) and tokens[j].type not in (tokenize.NEWLINE,
                                                                 tokenize.ENDMARKER):
                    t = tokens[j]
                    if t.type == tokenize.OP and t.string in "([{":
                        depth += 1
                    elif t.type == tokenize.OP and t.string in ")]}":
                        depth -= 1
                    if t.type not in (tokenize.COMMENT, tokenize.NL):
                        last = t
                    if depth == 0 and t.type == tokenize.OP and t.string == ";":
                        break
                    j += 1
                end = ")"
                if last is not None and last.type == tokenize.OP and last.string == ",":
                    edits.append((last.start, last.end, ', end=" ")'))
                    end = None
                first = tokens[i + 1]
                if first.type == tokenize.OP and first.string == ">>":
                    # print >>f, a, b  ->  print(a, b, file=f)
                    k = i + 2
                    while k < j and not (tokens[k].type == tokenize.OP and tokens[k].string == ","):
                        k += 1
                    target = _span(lines, tokens[i + 2].start, tokens[k - 1].end)
                    edits.append((tok.end, tokens[k].end if k < j else tokens[k - 1].end, "("))
                    if end is not None and last is not None:
                        edits.append((last.end, last.end, f", file={target})"))
                    elif end is None:
                        edits[-2] = (edits[-2][0], edits[-2][1], f', end=" ", file={target})')
                else:
                    edits.append((tok.end, tok.end, "("))
                    if end is not None and last is not None:
                        edits.append((last.end, last.end, ")"))
        at_start = False
        i += 1
    for (r0, c0), (r1, c1), text in sorted(edits, key=lambda e: (e[0], e[1]), reverse=True):
        if r0 == r1:
            line = lines[r0 - 1]
            lines[r0 - 1] = line[:c0] + text + line[c1:]
        else:
            lines[r0 - 1] = lines[r0 - 1][:c0] + text + "\n"
            lines[r1 - 1] = lines[r1 - 1][c1:]
    return "".join(lines)


def _span(lines, start, end) -> str:
    (r0, c0), (r1, c1) = start, end
    if r0 == r1:
        return lines[r0 - 1][c0:c1]
    return lines[r0 - 1][c0:] + "".join(lines[r0:r1 - 1]) + lines[r1 - 1][:c1]


def _register_modules(ns: dict) -> None:
    """AUTO's module names for helper files a script imports (`from AUTOclui import *`)."""
    import types
    if "AUTOclui" not in sys.modules:
        mod = types.ModuleType("AUTOclui", "washer's AUTO commands under AUTO's module name")
        mod.__dict__.update({k: v for k, v in ns.items() if not k.startswith("__")})
        sys.modules["AUTOclui"] = mod
    if "AUTOExceptions" not in sys.modules:
        # `except AUTOExceptions.AUTORuntimeError:` in a script catches a failed command
        mod = types.ModuleType("AUTOExceptions", "AUTO's exceptions: washer's AutoError")
        mod.AUTORuntimeError = clui.AutoError
        sys.modules["AUTOExceptions"] = mod


def auto(script):
    """AUTO's auto(script): run another AUTO script (in its own namespace, from the current
    folder)."""
    run_script(script)


def namespace() -> dict:
    """The names a script sees: AUTO's commands and aliases, and its objects."""
    ns = {"__name__": "__main__", "__builtins__": __builtins__}
    ns.update(clui.COMMANDS)
    ns["auto"] = auto
    from washer.auto import diagram
    ns.update(Diagram=diagram.Diagram, Solution=diagram.Solution,
              SolutionList=diagram.SolutionList, AutoError=clui.AutoError)
    _register_modules(ns)
    return ns


def run_script(path, ns: dict | None = None) -> dict:
    """Run an AUTO script in the current folder; raises ScriptError naming the line."""
    path = Path(path)
    try:
        source = path.read_text()
    except OSError as exc:
        raise ScriptError(f"{path}: cannot read the script ({exc.strerror})") from None
    text = translate(source)
    try:
        compiled = compile(text, str(path), "exec")
    except SyntaxError as exc:
        raise ScriptError(f"{path}:{exc.lineno}: syntax error: {exc.msg}") from None
    ns = namespace() if ns is None else ns
    ns["__file__"] = str(path)
    try:
        exec(compiled, ns)
    except SystemExit:
        raise
    except NameError as exc:
        line = _script_line(exc, path)
        name = getattr(exc, "name", None) or str(exc).split("'")[1:2] or [str(exc)]
        name = name if isinstance(name, str) else name[0]
        raise ScriptError(f"{path}:{line}: unknown command or name '{name}' "
                          f"({_source_line(source, line)}): washer's AUTO commands are "
                          f"{', '.join(sorted(set(clui.COMMANDS) | {'auto'}))}") from None
    except Exception as exc:        # noqa: BLE001 - every failure names the script line
        line = _script_line(exc, path)
        # KeyError's str() quotes its message; the label selections raise it with a sentence
        text = exc.args[0] if isinstance(exc, KeyError) and len(exc.args) == 1 and \
            isinstance(exc.args[0], str) else exc
        raise ScriptError(f"{path}:{line}: {type(exc).__name__}: {text} "
                          f"({_source_line(source, line)})") from exc
    return ns


def _script_line(exc: BaseException, path: Path):
    line = "?"
    for frame in traceback.extract_tb(exc.__traceback__):
        if frame.filename == str(path):
            line = frame.lineno
    return line


def _source_line(source: str, line) -> str:
    try:
        return source.splitlines()[int(line) - 1].strip()
    except (ValueError, IndexError):
        return ""


class Console(code.InteractiveConsole):
    """AUTO's prompt: commands predefined, print statements accepted."""

    def push(self, line: str) -> bool:
        return super().push(translate(line + "\n").rstrip("\n"))


def interact() -> None:
    sys.ps1, sys.ps2 = "AUTO> ", "..... "
    Console(namespace()).interact(banner="washer: AUTO's command language (run, load, save, "
                                         "append, merge, relabel, ...; Ctrl-D to leave)",
                                  exitmsg="")
