"""The commands' signatures and docstrings, made from the command line's own help
(``dpend COMMAND --help``, asked of the library once, at import): ``help(dpend.sweep)``
shows every option as a keyword argument with its type and the help text itself,
so the two never disagree. The options of a help line are its leading ``--name``
tokens; a name's type comes from the word after it (``N`` an int, ``LIST`` a
sequence, ``FILE`` a path, ``NAME`` a string, ``KG``/``S``/``RAD``... a float, no
word: a flag). ``output``, ``force``, ``quiet`` and ``help`` are the library's and
left out. Without the library the functions keep their short docstrings.
"""
from __future__ import annotations

import inspect
import os
import re
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

_OPTION = re.compile(r"--([a-z][a-z0-9-]*)")
_WORD = re.compile(r"[A-Z0-9][A-Z0-9_/^,|]*|[a-z]+(\|[a-z]+)+")   # N, M/S^2, rod|point
_LIBRARY_OWN = {"output", "force", "quiet", "help"}

_INT_WORDS = {"N", "K"}
_TEXT_WORDS = {"NAME", "NAMES", "U", "RULE", "D", "PATH", "rod|point", "q|theta"}
_SEQUENCE_WORDS = {"LIST", "AX,AY", "PX,PY"}

_TYPES: Dict[str, Any] = {
    "flag": bool,
    "int": int,
    "float": float,
    "text": str,
    "sequence": Union[Sequence[Any], str],
    "path": Union[str, "os.PathLike[str]"],
    "any": Any,
}


def _kind(word: Optional[str], description: str) -> str:
    """The type of an option whose value the help calls `word` (None: no word)."""
    if word is None:
        return "float" if "default" in description else "flag"
    if word in _INT_WORDS:
        return "int"
    if word == "FILE":
        return "path"
    if word in _TEXT_WORDS or "|" in word:
        return "text"
    if word in _SEQUENCE_WORDS or "," in word:
        return "sequence"
    return "float"


def parse_help(text: str) -> List[Tuple[str, str]]:
    """The options of a help text as (keyword, kind), in order, each once."""
    found: Dict[str, str] = {}
    for line in text.splitlines():
        stripped = line.lstrip()
        if not stripped.startswith("-") or not 2 <= len(line) - len(stripped) <= 4:
            continue
        gap = re.search(r"\S(\s{2,})\S", stripped)
        head = stripped[:gap.start(1)] if gap else stripped
        description = stripped[gap.end(1) - 1:] if gap else ""
        listed_only = gap is None            # a line that only lists options
        pending: List[str] = []
        for token in head.replace("(", " ").replace(")", " ").split():
            token = token.rstrip(",;")
            m = _OPTION.fullmatch(token)
            if m:
                pending.append(m.group(1))
            elif token and pending:       # a value's word, or a literal value
                if _WORD.fullmatch(token):
                    kind = _kind(token, description)
                elif listed_only:             # prose between the names
                    continue
                else:
                    kind = "text"             # --model elastic
                for name in pending:
                    found.setdefault(name, kind)
                pending = []
        for name in pending:
            found.setdefault(name, "any" if listed_only else _kind(None, description))
    return [(name.replace("-", "_") + ("_" if name == "lambda" else ""), kind)
            for name, kind in found.items() if name not in _LIBRARY_OWN]


def signature(text: str, positional: Sequence[str] = ()) -> inspect.Signature:
    """Keyword-only parameters (default None: the command's default) for the
    options of `text`, after `positional`, and ``**options`` for the others (a
    model's parameters, e.g. ``k=40``)."""
    params = [inspect.Parameter(p, inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                annotation=Union[str, "os.PathLike[str]"])
              for p in positional]
    taken = set(positional)
    for name, kind in parse_help(text):
        if name in taken or not name.isidentifier():
            continue
        taken.add(name)
        params.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY,
                                        default=None, annotation=Optional[_TYPES[kind]]))
    params.append(inspect.Parameter(
        "progress", inspect.Parameter.KEYWORD_ONLY, default="auto",
        annotation=Union[None, bool, str, Callable[[int, int, str, str], None]]))
    params.append(inspect.Parameter("options", inspect.Parameter.VAR_KEYWORD,
                                    annotation=Any))
    return inspect.Signature(params, return_annotation="xarray.Dataset")


_DOC_TAIL = """

Keyword arguments are the command line's options: ``t_end=1`` is ``--t-end 1``,
lists are Python sequences (``m=[1, 2]``), ``True`` gives a bare flag, ``None``
and ``False`` leave an option out (the command's default). Returns the file the
command writes as an xarray.Dataset; raises ValueError with the command line's
one line for refused input, dpend.RunError for a run that failed partway.
``progress``: "auto" a tqdm bar once the run has lasted a second (tqdm installed),
True at once, None none, or a callable f(done, total, what, label) (dpend.run).

The command's help (``dpend {command} --help``):

{help}"""


def document(functions: Dict[str, Callable[..., Any]],
             help_text: Callable[[str], str]) -> None:
    """Give each of `functions` (command name -> function) the signature and the
    docstring made from its help; a command whose help cannot be had keeps its own."""
    for command, f in functions.items():
        try:
            text = help_text(command)
        except Exception:                     # no library: the short docstrings stay
            return
        positional = ["data"] if command == "fit" else []
        f.__signature__ = signature(text, positional)      # type: ignore[attr-defined]
        f.__doc__ = (f.__doc__ or "").rstrip() + _DOC_TAIL.format(command=command,
                                                                   help=text)
