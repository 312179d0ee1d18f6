"""Presenting results: text for a terminal (and, later, Markdown, LaTeX, HTML, figures)."""
