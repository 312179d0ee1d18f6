"""A LaTeX document of a report (amsmath, graphicx and longtable only: any TeX installation has them).

Figures are included from files written beside the document (``files`` maps a figure key to its
relative path); an animation cannot live in a PDF, so its first frame's GIF is named instead.
"""

from __future__ import annotations

from .blocks import Animation, Document, Equations, Figure, Math, Paragraph, Step, Table
from .notation import latex, latex_condition, latex_text

PREAMBLE = r"""\documentclass[11pt,a4paper]{article}
\usepackage[T1]{fontenc}
\usepackage{amsmath,amssymb}
\usepackage{graphicx}
\usepackage{longtable,array}
\setlength{\textwidth}{16cm}\setlength{\oddsidemargin}{0cm}\setlength{\evensidemargin}{0cm}
\setlength{\parindent}{0pt}\setlength{\parskip}{0.5ex}
\allowdisplaybreaks
"""


def _tex(m: Math) -> str:
    return latex_condition(m.obj, m.relation) if m.relation is not None else latex(m.obj)


def _display(items) -> str:
    return "\n".join(rf"\[ {_tex(m)} \]" for m in items)


def _cell(c) -> str:
    return f"${_tex(c)}$" if isinstance(c, Math) else latex_text(str(c))


def _widths(table: Table, total: float = 15.0) -> list[float]:
    """Column widths (cm) in proportion to the length of their longest entry, within bounds."""
    def size(c):
        n = len(_tex(c)) / 3 if isinstance(c, Math) else len(str(c))
        return min(max(n, 4), 40)

    weights = [max([size(h)] + [size(r[i]) for r in table.rows]) for i, h in enumerate(table.columns)]
    return [total * w / sum(weights) for w in weights]


def _block(b, files: dict) -> str:
    if isinstance(b, Paragraph):
        return latex_text(b.text)
    if isinstance(b, Equations):
        return _display(b.items)
    if isinstance(b, Step):
        law = rf" \emph{{\small ({latex_text(b.law)})}}" if b.law else ""
        parts = [rf"\subsubsection*{{{latex_text(b.title)}{law}}}"]
        if b.equations:
            parts.append(_display(b.equations))
        if b.why:
            parts.append(rf"\emph{{{latex_text(b.why)}}}")
        return "\n".join(parts)
    if isinstance(b, Table):
        spec = "|" + "|".join(f">{{\\raggedright\\arraybackslash}}p{{{w:.2f}cm}}" for w in _widths(b)) + "|"
        head = " & ".join(rf"\textbf{{{latex_text(c)}}}" for c in b.columns)
        rows = "\n".join(" & ".join(_cell(c) for c in r) + r" \\ \hline" for r in b.rows)
        title = rf"\textbf{{{latex_text(b.caption)}}}" + "\n\n" if b.caption else ""
        return (f"{title}\\begin{{longtable}}{{{spec}}}\n\\hline {head} \\\\ \\hline\n\\endhead\n{rows}\n"
                "\\end{longtable}")
    if isinstance(b, Figure):
        path = files.get(b.key)
        if not path:
            return rf"\emph{{(Figure: {latex_text(b.caption)} It is in the HTML report.)}}"
        return (f"\\begin{{figure}}[htbp]\\centering\n\\includegraphics[width=\\linewidth]{{{path}}}\n"
                f"\\caption{{{latex_text(b.caption)}}}\n\\end{{figure}}")
    if isinstance(b, Animation):
        path = files.get(f"animation-{b.key}")
        where = f"the file \\texttt{{{latex_text(path)}}}" if path else "the HTML report"
        return rf"\emph{{{latex_text(b.caption)} The animation is in {where}.}}"
    raise TypeError(f"unknown block {b!r}")


def to_latex(doc: Document, files: dict | None = None) -> str:
    files = files or {}
    out = [PREAMBLE, rf"\title{{{latex_text(doc.title)}}}", rf"\author{{{latex_text(doc.subtitle)}}}", r"\date{}",
           r"\begin{document}", r"\maketitle"]
    for s in doc.sections:
        out.append(rf"\section{{{latex_text(s.title)}}}")
        out.extend(_block(b, files) for b in s.blocks)
    out.append(r"\end{document}")
    return "\n\n".join(out) + "\n"
