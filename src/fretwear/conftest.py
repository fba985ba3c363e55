"""Doctest collection of the package's modules (every module is collected)."""

collect_ignore: list[str] = []
