"""Printed results in plain ASCII, readable in any monospace font (``rigidkin --ascii``).

The text output writes a rate with a combining dot over its letter (θ̇, ẍ).  Many terminal fonts
(DejaVu Sans Mono among them) put a combining mark over the *next* glyph, so ``l·θ̇²`` can read ``l·θ²``.
The ASCII form has no combining mark and no letter outside ASCII: a rate is a prime after the name
(``theta'``, ``theta''``, ``x1'``), Greek letters are spelled (``theta``, ``mu``), powers are ``^2``,
products ``*``:  ``theta'' = 3*g*sin(theta)/(2*l)``.
"""

from __future__ import annotations

import re
import unicodedata

_PRIMES = {"\u0307": "'", "\u0308": "''", "\u20db": "'''"}
_SUPERSCRIPT = dict(zip("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺⁽⁾", "0123456789-+()", strict=True))
_SUBSCRIPT = dict(zip("₀₁₂₃₄₅₆₇₈₉", "0123456789", strict=True))
_SYMBOLS = {
    "·": "*", "×": "x", "−": "-", "–": "-", "—": "--", "≈": "~", "≤": "<=", "≥": ">=", "≠": "!=", "→": "->",
    "←": "<-", "⇒": "=>", "∞": "oo", "√": "sqrt", "°": " deg", "µ": "mu", "…": "...", "±": "+/-", "∓": "-/+",
    "‖": "||", "∂": "d", "∫": "int", "Σ": "Sum", "∈": " in ", "′": "'", "″": "''", "‘": "'", "’": "'", "“": '"',
    "”": '"', "\u00a0": " ", "⋅": "*", "∘": "o", "²": "^2", "³": "^3", "¹": "^1", "½": "1/2", "̂": "_hat",
}
# a letter, its combining marks (dots, hat), its subscript index, its _suffix: θ̇₁ → theta1', ẍ_B → x_B''
_MARKED = re.compile(r"([^\W\d_])([\u0300-\u036f\u20d0-\u20ff]+)([₀-₉]*)((?:_[A-Za-z0-9]+)?)")
_POWER = re.compile(r"[⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺⁽⁾]+")


def _letter(ch: str) -> str:
    """A character outside ASCII: a Greek letter by its name (θ → theta, Ω → Omega), a symbol by its usual
    ASCII form, anything else by its decomposition or its Unicode name."""
    if ch in _SYMBOLS:
        return _SYMBOLS[ch]
    if ch in _SUBSCRIPT:
        return _SUBSCRIPT[ch]
    name = unicodedata.name(ch, "")
    if name.startswith("GREEK SMALL LETTER ") or name.startswith("GREEK CAPITAL LETTER "):
        word = name.split("LETTER ", 1)[1].split()[0].lower()
        word = {"lamda": "lambda"}.get(word, word)
        return word if "SMALL" in name else word.capitalize()
    if name == "MICRO SIGN":
        return "mu"
    base = unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode()
    return base or (f"<{name.lower()}>" if name else "?")


def _marked(m: re.Match) -> str:
    letter, marks, index, tail = m.groups()
    primes = "".join(_PRIMES.get(c, "") for c in marks)
    other = "".join(_SYMBOLS.get(c, "") for c in marks if c not in _PRIMES)
    head = letter if letter.isascii() else _letter(letter)
    return head + "".join(_SUBSCRIPT[c] for c in index) + tail + other + primes


def to_ascii(text: str) -> str:
    """``text`` with every character outside ASCII written in ASCII: ``l·θ̇²`` → ``l*theta'^2``,
    ``θ̈₁`` → ``theta1''``, ``R_Ox ≈ 4.905`` → ``R_Ox ~ 4.905``; ASCII text is returned unchanged."""
    if text.isascii():
        return text
    text = unicodedata.normalize("NFD", text)          # ẍ (one code point) → x and its combining dots
    text = _MARKED.sub(_marked, text)
    text = _POWER.sub(lambda m: "^" + "".join(_SUPERSCRIPT[c] for c in m.group()), text)
    return "".join(c if c.isascii() else _letter(c) for c in text)


class AsciiStream:
    """A text stream that writes everything through :func:`to_ascii` (``sys.stdout`` under ``--ascii``)."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text: str) -> int:
        self._stream.write(to_ascii(text))
        return len(text)

    def __getattr__(self, name):
        return getattr(self._stream, name)
