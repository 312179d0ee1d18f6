"""Presenting results: the derivation as a document (text, Markdown, LaTeX, self-contained HTML), free-body
diagrams, plots of a simulation and an animation of the motion.

>>> import rigidkin as rk
>>> from rigidkin import examples, report
>>> doc = report.build_document(examples.build("ladder").solve(), figures=False, checks=False)
>>> [s.title for s in doc.sections][:3]
['Problem', 'Parameters and coordinates', 'Frames and coordinates']
"""

from .document import REPORT_SECTIONS, Document, build_document
from .output import render, write_document, write_report


def free_body_diagram(obj, **kwargs):
    """Free-body diagrams of a System or Solution (see :func:`rigidkin.report.fbd.free_body_diagram`)."""
    from .fbd import free_body_diagram as fbd

    return fbd(obj, **kwargs)


__all__ = ["Document", "REPORT_SECTIONS", "build_document", "render", "write_document", "write_report",
           "free_body_diagram"]
