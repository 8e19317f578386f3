"""Build hook (the metadata is in pyproject.toml): after the package's files are copied to the build tree, solve the
shipped Test 1 robot once there (``cdpr warm``, :mod:`cdpr_algebra.cli.warm`), so that numba's compiled kernels are
cached inside the built package and the first run after ``pip install .`` does not compile them (issue 19 item 5).
numba keys its cache on the sources' contents, its version and the CPU, so a cache built elsewhere is ignored, never
wrong.  Never fails the build: without a cache the kernels are compiled on first use, as before."""

import os
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py

EXAMPLE = os.path.join("examples", "seed000_test1.toml")


def warm_environment(build_lib: str, environ) -> dict:
    """The environment of the warm-up process: the built package first on the path, then whatever pip put there
    (under build isolation, the build environment with the requirements of pyproject.toml: replacing it left the
    warm-up without numpy on a fresh machine, so nothing was cached and the first run compiled for ~55 s), and no
    NUMBA_CACHE_DIR (the caches must land in the built package)."""
    path = [build_lib] + [p for p in environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    env = dict(environ, PYTHONPATH=os.pathsep.join(path))
    env.pop("NUMBA_CACHE_DIR", None)
    return env


class build_py_warm(build_py):
    def run(self):
        super().run()
        if os.environ.get("CDPR_ALGEBRA_NO_WARM") or not os.path.exists(EXAMPLE):
            return
        build_lib = os.path.abspath(self.build_lib)
        env = warm_environment(build_lib, os.environ)
        print("cdpr_algebra: compiling the numeric kernels into the build (cdpr warm; CDPR_ALGEBRA_NO_WARM=1 skips)")
        try:
            # run in the build tree: the package imported (and its caches) must be the built one, not the sources
            run = subprocess.run([sys.executable, "-m", "cdpr_algebra", "warm", os.path.abspath(EXAMPLE)], env=env,
                                 cwd=build_lib, capture_output=True, text=True, timeout=1800)
            print(run.stdout + run.stderr if run.returncode else run.stdout)
        except (OSError, subprocess.SubprocessError) as err:
            print(f"cdpr_algebra: kernels not precompiled ({err}); they compile on first use")


if __name__ == "__main__":  # as pip's build backend runs it (setuptools.build_meta); a test imports the helpers
    setup(cmdclass={"build_py": build_py_warm})
