# The README's Python example runs as printed and writes its plot; every link of the README and
# the user guide (docs/) resolves; the README's method table is the one docs/accuracy.md holds.
import importlib.util
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


LINK = re.compile(r"\]\(([^)\s]+)\)")


def broken_links(page):
    """The relative link targets of a markdown page that do not exist (URLs and anchors skipped)."""
    targets = LINK.findall(page.read_text())
    return [t for t in targets if not re.match(r"[a-z]+://|#|mailto:", t)
            and not (page.parent / t.split("#")[0]).exists()]


def test_every_link_of_the_readme_and_the_user_guide_resolves(tmp_path):
    pages = [SOURCE_DIR / "README.md", *sorted((SOURCE_DIR / "docs").glob("*.md"))]
    broken = {page.name: broken_links(page) for page in pages}
    assert not any(broken.values()), broken
    assert len(LINK.findall((SOURCE_DIR / "README.md").read_text())) >= 10
    # negative control: a link to a missing page is found, URLs, anchors and existing pages not
    page = tmp_path / "page.md"
    page.write_text("[a](missing.md) [b](https://example.org) [c](#top) [d](page.md#top)")
    assert broken_links(page) == ["missing.md"]


def test_the_readme_method_table_is_the_one_docs_accuracy_md_holds():
    script = SOURCE_DIR / "scripts" / "readme_tables.py"
    done = subprocess.run([sys.executable, str(script), "--check"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    # negative control: a README whose table differs is not current
    spec = importlib.util.spec_from_file_location("readme_tables", script)
    tables = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tables)
    readme = (SOURCE_DIR / "README.md").read_text()
    assert tables.updated(readme, "| method |\n|---|\n| Typed | 1 | 1 | 1.00 |\n") != readme
