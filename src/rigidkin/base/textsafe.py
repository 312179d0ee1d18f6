"""Text from a problem file, made safe for wherever it is shown: code, terminals, HTML, Markdown, LaTeX,
CSV cells and file names.

A problem file may come from a stranger.  Its free text (title, statement, descriptions, senses) and
its names are *shown* — never run: generated code contains only rigidkin's own names
(:mod:`rigidkin.numeric.compiled.codegen`), and every output format escapes what it shows with these helpers.
Each helper takes any text and returns text that the target reads literally.
"""

from __future__ import annotations

import html
import keyword
import re
import unicodedata

#: The longest name an identifier may have.
MAX_IDENTIFIER = 64

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

_C_WORDS = """
auto break case char const continue default do double else enum extern float for goto if inline int long
register restrict return short signed sizeof static struct switch typedef union unsigned void volatile while
_Alignas _Alignof _Atomic _Bool _Complex _Generic _Imaginary _Noreturn _Static_assert _Thread_local
alignas alignof bool constexpr false nullptr static_assert thread_local true typeof typeof_unqual
asm catch class const_cast delete dynamic_cast explicit export friend mutable namespace new operator private
protected public reinterpret_cast static_cast template this throw try typeid typename using virtual wchar_t
defined NULL
"""
#: C (C89 to C23) and C++ keywords (and ``defined``, ``NULL``): never a name in generated code.
C_RESERVED = frozenset(_C_WORDS.split())


def is_identifier(name: object, max_length: int = MAX_IDENTIFIER) -> bool:
    """True for an ASCII identifier ``[A-Za-z_][A-Za-z0-9_]*`` of at most ``max_length`` characters that is
    no C, C++ or Python keyword and does not begin with two underscores (names reserved to compilers)."""
    return (isinstance(name, str) and 0 < len(name) <= max_length and _IDENTIFIER.fullmatch(name) is not None
            and name not in C_RESERVED and not keyword.iskeyword(name) and not keyword.issoftkeyword(name)
            and not name.startswith("__"))


# terminals ----------------------------------------------------------------------------------------------
_BIDI = {"\u061c", "\u200e", "\u200f", "\u202a", "\u202b", "\u202c", "\u202d", "\u202e",
         "\u2066", "\u2067", "\u2068", "\u2069"}


def _is_control(ch: str) -> bool:
    return unicodedata.category(ch) in ("Cc", "Cf", "Cs", "Co", "Cn") and ch not in "\u200d" or ch in _BIDI


def terminal_safe(text: object, newlines: bool = True) -> str:
    """``text`` for a terminal or a log: control characters (escape sequences, carriage returns, bells,
    bidirectional overrides, ...) written as visible escapes such as ``\\x1b``; newlines and tabs are kept
    when ``newlines``."""
    out = []
    for ch in str(text):
        if newlines and ch in "\n\t":
            out.append(ch)
        elif _is_control(ch):
            out.append(f"\\x{ord(ch):02x}" if ord(ch) < 0x100 else f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return "".join(out)


def _printable(text: object) -> str:
    """Control characters other than newline and tab dropped (no format can show them usefully)."""
    return "".join(ch for ch in str(text) if ch in "\n\t" or not _is_control(ch))


def figure_text(text: object) -> str:
    """Text for a matplotlib title or label, shown as it is: no control characters, and ``$`` escaped so
    that nothing is read as mathtext."""
    return _printable(text).replace("$", r"\$")


# HTML and Markdown ----------------------------------------------------------------------------------------
def html_text(text: object) -> str:
    """Text for HTML content or a quoted attribute value: ``& < > " '`` as character references."""
    return html.escape(_printable(text), quote=True)


_MARKDOWN_SPECIAL = re.compile(r"([\\`*_{}\[\]#|$~])")


def markdown_text(text: object, inline: bool = True) -> str:
    """Text for Markdown, shown as it is: no raw HTML (``< > &`` as character references), no emphasis,
    code, link, image, heading, table cell or math (``\\ ` * _ { } [ ] # | $ ~`` backslash-escaped).
    ``inline``: newlines become spaces (headings, table cells, emphasis)."""
    s = _printable(text)
    if inline:
        s = re.sub(r"\s*\n\s*", " ", s)
    s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return _MARKDOWN_SPECIAL.sub(r"\\\1", s)


# LaTeX ----------------------------------------------------------------------------------------------------
_TEX_SPECIAL = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&", "#": r"\#",
                "%": r"\%", "_": r"\_", "^": r"\textasciicircum{}", "~": r"\textasciitilde{}"}


def tex_text(text: object) -> str:
    """Text for a TeX document, read as letters only: every character with a meaning to TeX escaped (so no
    ``\\input``, ``\\write18``, ``^^5c`` or catcode change survives), control characters dropped."""
    return "".join(_TEX_SPECIAL.get(ch, ch) for ch in _printable(text).replace("\r", ""))


# CSV ----------------------------------------------------------------------------------------------------------
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "\n", "\uff1d", "\uff0b", "\uff0d", "\uff20")
_NUMBER = re.compile(r"[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?|[+-]?(inf|infinity|nan)", re.IGNORECASE)


def safe_csv_cell(value):
    """A value for a CSV cell that no spreadsheet runs as a formula.

    Numbers (and text that is a plain number, such as ``-1.5``) are returned unchanged; text that a
    spreadsheet would read as a formula or a command (beginning with ``= + - @``, a tab or a line
    break, after any spaces) gets a leading apostrophe, which spreadsheets show as text.
    """
    if value is None or isinstance(value, (bool, int, float, complex)) or not isinstance(value, str) and \
            hasattr(value, "dtype"):
        return value
    s = str(value)
    if _NUMBER.fullmatch(s.strip()):
        return s
    if s.lstrip(" ").startswith(_FORMULA_START):
        return "'" + s
    return s


# file names ---------------------------------------------------------------------------------------------
_WINDOWS_DEVICES = {"con", "prn", "aux", "nul", *(f"com{i}" for i in range(10)), *(f"lpt{i}" for i in range(10))}


def safe_filename(text: object, default: str = "untitled", max_length: int = 80) -> str:
    """A file name (no folder) made from user text: letters, digits, ``. _ -`` only (anything else
    becomes ``_``), no path separator, never ``.`` or ``..`` or a hidden name, at most ``max_length``
    characters; ``default`` when nothing usable is left."""
    s = unicodedata.normalize("NFKD", _printable(text))
    s = "".join(ch for ch in s if not unicodedata.combining(ch))
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", s).strip("._-")
    s = re.sub(r"\.{2,}", ".", s)[:max_length].strip("._-")
    if not s or s.split(".")[0].lower() in _WINDOWS_DEVICES:
        s = f"{default}_{s}" if s else default
    return s
