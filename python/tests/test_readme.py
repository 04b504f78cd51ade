# The README's Python example runs as printed and writes its plot.
import os
import pathlib
import re
import subprocess
import sys

import erkn
from conftest import SOURCE_DIR


def readme_example():
    readme = SOURCE_DIR / "README.md"
    section = readme.read_text().split("\n## Python", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert blocks, "README.md has no ```python block in its Python section"
    return blocks[0]


def test_readme_python_example_runs_and_writes_its_plot(tmp_path):
    code = readme_example()
    plot = re.search(r"savefig\(\"([^\"]+)\"", code).group(1)
    package_root = pathlib.Path(erkn.__file__).resolve().parent.parent  # (the erkn under test)
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(package_root))
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / plot).stat().st_size > 10000
    assert "energy" in done.stdout
