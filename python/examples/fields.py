"""The fields of the package's result types, with their meaning and units, as the package's own
docstrings state them.

    python3 python/examples/fields.py
"""

from __future__ import annotations

import ast
import inspect
import textwrap

import oblique

TYPES = ("Rebound", "Rebound2D", "Impact", "Simulation", "Groups")


def fields(tree: ast.Module, name: str) -> list[tuple[str, str]]:
    """(field, docstring) of class ``name``: each annotated field and the string after it."""
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == name)
    out: list[tuple[str, str]] = []
    for i, node in enumerate(cls.body):
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            after = cls.body[i + 1] if i + 1 < len(cls.body) else None
            doc = ""
            if (
                isinstance(after, ast.Expr)
                and isinstance(after.value, ast.Constant)
                and isinstance(after.value.value, str)
            ):
                doc = " ".join(after.value.value.split())
            out.append((node.target.id, doc))
    return out


tree = ast.parse(inspect.getsource(oblique))
undocumented = []
for name in TYPES:
    print(name)
    for field, doc in fields(tree, name):
        if not doc:
            undocumented.append(f"{name}.{field}")
        text = textwrap.fill(
            f"{field}: {doc}",
            width=96,
            initial_indent="  ",
            subsequent_indent="      ",
        )
        print(text)
if undocumented:
    raise SystemExit(f"fields without a docstring: {', '.join(undocumented)}")
