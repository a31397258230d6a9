"""Where the gallery finds the real data files: vendored under examples/, else shared/data."""

from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def find(*parts: str) -> Path:
    """The first existing copy of ``shared/data/<parts>``: vendored under ``examples/``, or in
    ``shared/`` beside the project (or beside its folder of work trees)."""
    candidates = [ROOT / "examples" / parts[0] / Path(*parts[1:])]
    candidates += [r / "shared" / "data" / Path(*parts) for r in (ROOT.parent, ROOT.parents[1])]
    for c in candidates:
        if c.exists():
            return c
    raise FileNotFoundError(f"shared/data/{'/'.join(parts)} not found; looked in "
                            + ", ".join(str(c) for c in candidates))
