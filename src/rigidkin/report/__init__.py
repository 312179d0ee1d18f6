"""Presenting results: the derivation as a document (text, Markdown, LaTeX, self-contained HTML), free-body
diagrams, plots of a simulation and an animation of the motion.

The names below are loaded when first used, so that importing one module of this package (the plain-text
solution, the notation) runs neither the document builder nor matplotlib.

>>> import rigidkin as rk
>>> from rigidkin import examples, report
>>> doc = report.build_document(examples.build("ladder").solve(), figures=False, checks=False)
>>> [s.title for s in doc.sections][:3]
['Problem', 'Parameters and coordinates', 'Frames and coordinates']
"""

from __future__ import annotations

from ..base.lazy import names_on_first_use

#: public name → the module of this package that defines it
_LAZY = {"Document": ".blocks", "REPORT_SECTIONS": ".document", "build_document": ".document",
         "render": ".output", "write_document": ".output", "write_report": ".output",
         "free_body_diagram": ".fbd"}

__all__ = ["Document", "REPORT_SECTIONS", "build_document", "render", "write_document", "write_report",
           "free_body_diagram"]


__getattr__ = names_on_first_use(__name__, _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
