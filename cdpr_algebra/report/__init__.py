"""Rendering of results: JSON-ready values, text tables, matplotlib pictures (knows no problem; results use it to render themselves)."""
