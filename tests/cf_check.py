"""The CF 1.8 errors (high-priority failures) compliance-checker finds in each file named on the
command line, printed as one JSON object {path: [messages]}. Tests run it in its own process:
compliance-checker and xarray opening the same HDF5 files in one process can crash."""

import json
import sys
import warnings


def main(paths: list[str]) -> dict[str, list[str]]:
    warnings.simplefilter("ignore")
    from compliance_checker.runner import CheckSuite

    suite = CheckSuite()
    suite.load_all_available_checkers()
    out = {}
    for path in paths:
        results, _ = suite.run_all(suite.load_dataset(path), ["cf:1.8"],
                                   skip_checks=[])["cf:1.8"]
        out[path] = _errors(results)
    return out


def _errors(results) -> list[str]:
    errors: list[str] = []
    for r in results:
        if r.weight == 3 and r.value is not None:
            ok = r.value if isinstance(r.value, bool) else r.value[0] == r.value[1]
            if not ok:
                errors.extend(r.msgs or [r.name])
        errors += _errors(r.children or [])
    return errors


def cf_errors(paths, processes: int = 2) -> dict[str, list[str]]:
    """:func:`main` on ``paths`` in new processes, the files shared out among them.

    The checker takes about a second and a half a file, on one core: the processes check
    their shares at once.
    """
    import os
    import subprocess

    paths = [str(p) for p in paths]
    n = max(1, min(processes, os.cpu_count() or 1, len(paths)))
    running = [subprocess.Popen([sys.executable, __file__, *paths[i::n]], text=True,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
               for i in range(n)]
    out: dict[str, list[str]] = {}
    for proc in running:
        stdout, stderr = proc.communicate()
        assert proc.returncode == 0, stderr
        out.update(json.loads(stdout.strip().splitlines()[-1]))
    return out


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1:])))
