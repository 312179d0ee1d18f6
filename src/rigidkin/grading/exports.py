"""A problem set for a learning platform: Moodle XML, or PrairieLearn question folders.

Every question says what is asked, in words and symbol, with its SI unit ("give φ, the angle of the line
of centres OC from the upward vertical, in rad").  Every text that came from the problem file is escaped
for HTML (and then for XML by ElementTree, or written into JSON and a Python literal by ``json``/``repr``).
"""

from __future__ import annotations

import json
import re
import uuid
import xml.etree.ElementTree as ET
from pathlib import Path

from ..base.errors import InputError
from ..base.textsafe import html_text
from .variants import KeyEntry, ProblemSet


def asked_text(ps: ProblemSet, k: KeyEntry) -> str:
    """What a key asks, in words: 'where the sphere leaves ...: give φ (angle ...) in rad'."""
    what = k.symbol or k.label
    if k.words:
        what += f" ({k.words})"
    extra = k.at
    unit = f", in {k.unit}" if k.unit else ""
    return f"{ps.questions.get(k.question, k.question)}: give {what}{extra}{unit}."


def _values_html(v) -> str:
    return "".join(f"<li>{html_text(n)} = {html_text(f'{x:g}')} {html_text(v.units[n])}</li>"
                   for n, x in sorted({**v.fixed, **v.values}.items()))


def as_moodle(ps: ProblemSet) -> str:
    """Moodle XML: one numerical question per variant and answer."""
    quiz = ET.Element("quiz")
    cat = ET.SubElement(quiz, "question", type="category")
    ET.SubElement(ET.SubElement(cat, "category"), "text").text = f"$course$/rigidkin/{_plain(ps.title)}"
    for v in ps.variants:
        vals = _values_html(v)
        for k in v.keys:
            q = ET.SubElement(quiz, "question", type="numerical")
            ET.SubElement(ET.SubElement(q, "name"), "text").text = _plain(
                f"{ps.title} — variant {v.index} — {k.question}: {k.symbol or k.label}")
            body = (f"<p>{html_text(ps.statement)}</p><p>Values:</p><ul>{vals}</ul>"
                    f"<p>{html_text(asked_text(ps, k))}</p>")
            qt = ET.SubElement(q, "questiontext", format="html")
            ET.SubElement(qt, "text").text = _plain(body)
            ET.SubElement(q, "defaultgrade").text = "1"
            ans = ET.SubElement(q, "answer", fraction="100")
            ET.SubElement(ans, "text").text = repr(float(k.value))
            ET.SubElement(ans, "tolerance").text = repr(float(k.tolerance))
            fb = ET.SubElement(ans, "feedback", format="html")
            ET.SubElement(fb, "text").text = f"<p>{html_text(k.exact)}</p>" if k.exact else ""
            if k.unit:
                units = ET.SubElement(q, "units")
                u = ET.SubElement(units, "unit")
                ET.SubElement(u, "multiplier").text = "1"
                ET.SubElement(u, "unit_name").text = _plain(k.unit)
    ET.indent(quiz)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(quiz, encoding="unicode") + "\n"


def as_prairielearn(ps: ProblemSet, folder) -> list[Path]:
    """PrairieLearn: one question folder per variant (``info.json``, ``question.html``, ``server.py``), each
    with a ``pl-number-input`` per key; the keys are set in ``server.py`` (data only, no computation)."""
    root = Path(folder)
    if root.exists() and not root.is_dir():
        raise InputError("is not a folder.", where=str(root), hint="Give a folder for the PrairieLearn questions.")
    out = []
    slug = _slug(ps.title) or "problem"
    for v in ps.variants:
        d = root / f"{slug}-v{v.index}"
        d.mkdir(parents=True, exist_ok=True)
        qid = uuid.uuid5(uuid.NAMESPACE_URL, f"rigidkin:{ps.problem}:{ps.title}:{v.index}")
        info = {"uuid": str(qid), "title": f"{ps.title} (variant {v.index})", "topic": "Rigid-body kinetics",
                "tags": ["rigidkin", slug], "type": "v3"}
        inputs, answers = [], {}
        for i, k in enumerate(v.keys):
            name = f"a{i + 1}"
            answers[name] = float(k.value)
            rtol = k.tolerance / abs(k.value) if k.value else 0.0
            atol = float(k.tolerance) if not k.value else 1e-12 * abs(k.value)
            inputs.append(f"<p>{html_text(asked_text(ps, k))}</p>\n<pl-number-input answers-name=\"{name}\" "
                          f"comparison=\"relabs\" rtol=\"{rtol:.6g}\" atol=\"{atol:.6g}\" "
                          f"suffix=\"{html_text(k.unit)}\"></pl-number-input>")
        html = (f"<pl-question-panel>\n<p>{html_text(ps.statement)}</p>\n<p>Values:</p><ul>{_values_html(v)}</ul>\n"
                "</pl-question-panel>\n" + "\n".join(inputs) + "\n")
        server = ("# written by rigidkin variants: the keys of this variant, solved and checked by rigidkin\n"
                  f"ANSWERS = {json.dumps(answers)!r}\n\n\n"
                  "def generate(data):\n    import json\n\n"
                  "    data[\"correct_answers\"].update(json.loads(ANSWERS))\n")
        (d / "info.json").write_text(json.dumps(info, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
        (d / "question.html").write_text(html, encoding="utf-8")
        (d / "server.py").write_text(server, encoding="utf-8")
        out.append(d)
    return out


def _slug(s: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", s.lower()).strip("-")[:60]


def _plain(s: str) -> str:
    """Text for an XML text node: characters XML 1.0 cannot hold removed (ElementTree escapes the rest)."""
    return "".join(ch for ch in str(s) if ch in "\t\n\r" or (ord(ch) >= 0x20 and not 0xD800 <= ord(ch) <= 0xDFFF
                                                              and ch not in "\ufffe\uffff"))
