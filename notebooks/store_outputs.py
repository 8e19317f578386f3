"""Execute the teaching notebooks top to bottom and store them with their outputs (pictures visible on any
notebook viewer without running them).  Run from the repository root after the package is installed:

    python3 notebooks/store_outputs.py [NAME.ipynb ...]

The kernel is this interpreter (a kernelspec for ``sys.executable`` in a temporary directory), the working
directory the notebooks' folder; any error stops with a non-zero exit status and leaves the notebook unchanged.
``tests/test_notebooks.py`` checks that the stored outputs come from one top-to-bottom run without errors and
executes every notebook again.
"""

import sys
import tempfile
from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent


def kernel_manager(kernel_dir: Path):
    from ipykernel.kernelspec import write_kernel_spec
    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager

    if not (kernel_dir / "python3").exists():
        write_kernel_spec(kernel_dir / "python3")
    ksm = KernelSpecManager(kernel_dirs=[str(kernel_dir)])
    return KernelManager(kernel_name="python3", kernel_spec_manager=ksm)


def execute(path: Path, kernel_dir: Path, timeout: int = 600):
    """The notebook at ``path`` executed (nbclient); raises CellExecutionError on the first failing cell."""
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, km=kernel_manager(kernel_dir), timeout=timeout, allow_errors=False,
                            resources={"metadata": {"path": str(path.parent)}})
    client.execute()
    return nb


def main(argv=None) -> int:
    names = (argv if argv is not None else sys.argv[1:]) or sorted(p.name for p in HERE.glob("*.ipynb"))
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            path = HERE / name
            nb = execute(path, Path(tmp))
            nb.metadata.pop("widgets", None)
            nbformat.validate(nb)
            nbformat.write(nb, path)
            print(f"{name}: executed and stored with outputs", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
