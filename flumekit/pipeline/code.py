"""The code a rule runs, as a hash of its source: a code change rebuilds what it changes.

A rule's action is ``"flumekit.<module>:<function>"``. Its code hash covers the source of that
module and of every flumekit module it imports, directly or through others (at module level or
inside a function), found by reading the source, never by importing it (planning stays free of
numpy). Two rules of the import graph's reach:

- a package's ``__init__`` stands for every module of that package (a facade may name its
  modules in strings, imported on first use), except the root ``flumekit`` package: the
  public facade over everything, whose own source (the version) counts but whose imports are
  not followed;
- ``importlib.import_module(f"flumekit.<package>.{...}")`` (a module chosen by a parameter,
  as the figures stage does) stands for every module of that package.

A hand-bumped rule ``version`` stays an extra: it changes the key on its own.
"""

from __future__ import annotations

import functools
import hashlib
import os
import re

#: the flumekit package folder
PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_IMPORT = re.compile(r"^[ \t]*(?:from[ \t]+(flumekit(?:\.\w+)*)[ \t]+import[ \t]+(\([^)]*\)|[^\n]*)"
                     r"|import[ \t]+(flumekit(?:\.\w+)*))", re.M)
_DYNAMIC = re.compile(r"import_module\(\s*f[\"'](flumekit(?:\.\w+)+)\.\{")


def module_file(name: str) -> str | None:
    """Return the source file of a flumekit module.

    Parameters
    ----------
    name : str
        Dotted module name, e.g. ``"flumekit.waves.spectra"``.

    Returns
    -------
    str or None
        Path of its ``.py`` file (a package's ``__init__.py``); None when ``name`` is not a
        module of the package.

    Examples
    --------
    >>> module_file("flumekit.pipeline.code").endswith("code.py")
    True
    >>> module_file("numpy") is None
    True
    """
    parts = name.split(".")
    if parts[0] != "flumekit":
        return None
    base = os.path.join(PACKAGE_DIR, *parts[1:])
    if os.path.isfile(os.path.join(base, "__init__.py")):
        return os.path.join(base, "__init__.py")
    if os.path.isfile(base + ".py"):
        return base + ".py"
    return None


def _package_modules(package: str) -> list[str]:
    """Return the modules directly in a flumekit package (its ``__init__`` excluded)."""
    folder = os.path.join(PACKAGE_DIR, *package.split(".")[1:])
    out = []
    for entry in sorted(os.listdir(folder)):
        stem, ext = os.path.splitext(entry)
        if ext == ".py" and stem != "__init__":
            out.append(f"{package}.{stem}")
        elif os.path.isfile(os.path.join(folder, entry, "__init__.py")):
            out.append(f"{package}.{entry}")
    return out


@functools.cache
def _imports(name: str) -> tuple[str, ...]:
    """Return the flumekit modules module ``name`` imports (module level and in functions)."""
    path = module_file(name)
    if name == "flumekit":  # the facade: read for its version, not followed
        return ()
    with open(path, encoding="utf-8") as f:
        source = f.read()
    found: set[str] = set()
    for frm, names, imp in _IMPORT.findall(source):
        if imp:
            if module_file(imp):
                found.add(imp)
            continue
        # `from pkg import sub, name`: the submodules, and the package for any other name
        others = False
        listed = re.sub(r"#[^\n]*", "", names).strip("() \t\n\\")
        for n in (x.split()[0] for x in re.split(r"[,\n]", listed) if x.strip()):
            if module_file(f"{frm}.{n}"):
                found.add(f"{frm}.{n}")
            else:
                others = True
        if others and module_file(frm):
            found.add(frm)
    for package in _DYNAMIC.findall(source):
        if module_file(package):
            found.update(_package_modules(package))
    if path.endswith("__init__.py"):
        found.update(_package_modules(name))
    found.discard(name)
    return tuple(sorted(found))


def closure(name: str) -> list[str]:
    """Return a module and every flumekit module it reaches through imports.

    Parameters
    ----------
    name : str
        Dotted flumekit module name.

    Returns
    -------
    list of str
        ``name`` and the modules it reaches, sorted.

    Examples
    --------
    >>> "flumekit.pipeline.code" in closure("flumekit.pipeline.code")
    True
    """
    seen = {name}
    todo = [name]
    while todo:
        for m in _imports(todo.pop()):
            if m not in seen:
                seen.add(m)
                todo.append(m)
    return sorted(seen)


@functools.cache
def code_hash(action: str) -> str:
    """SHA-256 of the source of every module an action's code reaches (:func:`closure`).

    Parameters
    ----------
    action : str
        ``"module:function"``.

    Returns
    -------
    str
        The hex digest; empty for an action outside the flumekit package (its code is not
        tracked).

    Examples
    --------
    >>> len(code_hash("flumekit.stages.waves:build"))
    64
    >>> code_hash("my_lab_actions:build")
    ''
    """
    module = action.partition(":")[0]
    if module_file(module) is None:
        return ""
    h = hashlib.sha256()
    for m in closure(module):
        with open(module_file(m), "rb") as f:
            h.update(f"{m}\0{hashlib.sha256(f.read()).hexdigest()}\n".encode())
    return h.hexdigest()


__all__ = ["PACKAGE_DIR", "closure", "code_hash", "module_file"]
