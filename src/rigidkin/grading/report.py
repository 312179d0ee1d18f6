"""A graded worksheet as text, JSON or one self-contained HTML page.

The HTML page is written for the student: each step's claim beside the engine's form, the verdict, the
causes, and the differing terms highlighted (theirs struck through in red, the engine's in green).
Everything that came from the worksheet or the problem file is escaped
(:func:`rigidkin.base.textsafe.html_text`); the page loads nothing and runs no script.
"""

from __future__ import annotations

from ..base.textsafe import html_text, terminal_safe
from .verdicts import CORRECT, GradeReport

_MARK = {"correct": "✓", "incorrect": "✗", "unreadable": "?"}


def as_text(report: GradeReport) -> str:
    head = f"Worksheet on {report.title}" + (f" by {report.student}" if report.student else "")
    lines = [terminal_safe(head, newlines=False)]
    for s in report.steps:
        lines.append(terminal_safe(f"Step {s.index} ({s.kind}): {_MARK[s.verdict]} {s.verdict}", newlines=False))
        if s.asks:
            lines.append("    the question asks: " + terminal_safe(s.asks, newlines=False))
        for f in s.feedback:
            lines.append("    " + terminal_safe(f, newlines=False))
        if s.verdict != CORRECT and s.expected:
            lines.append("    engine: " + terminal_safe(s.expected, newlines=False))
    lines.append(f"Score: {report.correct} of {len(report.steps)} steps correct ({report.score:.0%}).")
    return "\n".join(lines)


def as_data(report: GradeReport) -> dict:
    return {
        "problem": report.problem,
        "title": report.title,
        "student": report.student,
        "steps": [{"index": s.index, "kind": s.kind, "verdict": s.verdict, "feedback": list(s.feedback),
                   "claim": s.claim, "expected": s.expected, "carried_from": list(s.carried_from),
                   "asks": s.asks}
                  for s in report.steps],
        "correct": report.correct,
        "total": len(report.steps),
        "score": report.score,
    }


_CSS = """
body{font-family:system-ui,sans-serif;max-width:70em;margin:2em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;width:100%}td,th{border:1px solid #ccc;padding:.4em .6em;vertical-align:top}
th{background:#f4f4f4;text-align:left}.correct{background:#eef9ee}.incorrect{background:#fdf0f0}
.unreadable{background:#fff8e0}code{font-family:ui-monospace,monospace;white-space:pre-wrap}
del{color:#b00;text-decoration:line-through}ins{color:#070;text-decoration:none;font-weight:bold}
.verdict{font-weight:bold}ul{margin:.2em 0;padding-left:1.2em}
"""


def as_html(report: GradeReport) -> str:
    h = html_text
    rows = []
    for s in report.steps:
        fb = "".join(f"<li>{h(f)}</li>" for f in s.feedback)
        diffs = "".join(f"<li>{'<del>' + h(a) + '</del>' if a else ''}"
                        f"{' → ' if a and b else ''}{'<ins>' + h(b) + '</ins>' if b else ''}</li>"
                        for a, b in s.differences)
        carried = (f"<p>Carried from step{'s' if len(s.carried_from) > 1 else ''} "
                   f"{h(', '.join(map(str, s.carried_from)))}.</p>" if s.carried_from else "")
        rows.append(
            f"<tr class=\"{h(s.verdict)}\"><td>{s.index}</td><td>{h(s.kind)}</td>"
            f"<td><code>{h(s.claim)}</code>{'<p>The question asks: ' + h(s.asks) + '</p>' if s.asks else ''}</td>"
            f"<td><code>{h(s.expected) if s.verdict != CORRECT or s.expected else ''}</code></td>"
            f"<td><span class=\"verdict\">{h(_MARK[s.verdict])} {h(s.verdict)}</span>"
            f"{'<ul>' + fb + '</ul>' if fb else ''}"
            f"{'<p>Differences (yours → expected):</p><ul>' + diffs + '</ul>' if diffs else ''}{carried}</td></tr>")
    who = f" — {h(report.student)}" if report.student else ""
    return (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">"
        f"<title>Graded worksheet: {h(report.title)}</title><style>{_CSS}</style></head><body>"
        f"<h1>Graded worksheet: {h(report.title)}{who}</h1>"
        f"<p>Problem: <code>{h(report.problem)}</code>. Score: {report.correct} of {len(report.steps)} steps "
        f"correct ({report.score:.0%}).</p>"
        "<table><thead><tr><th>#</th><th>step</th><th>you wrote</th><th>the engine's form</th>"
        "<th>verdict and why</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>"
        "<p>Equivalent forms are accepted: any nonzero factor, any arrangement, any valid combination of the "
        "balance equations. A carried error is a step that follows correctly from an earlier wrong one.</p>"
        "</body></html>\n")
