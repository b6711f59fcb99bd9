"""The Python session of the user guide (docs/python.md) runs as written
(doctest), in a directory holding the map of jobs/examples/quick.ini."""
import doctest
import os
import re
import subprocess


def test_docs_python_session(exe, srcdir, tmp_path):
    with open(f"{srcdir}/docs/python.md") as f:
        page = f.read()
    blocks = re.findall(r"```python\n(.*?)```", page, re.S)
    session = [b for b in blocks if b.startswith(">>> ")]
    assert len(session) == 1
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([exe, "study", "--quiet", "--config", f"{srcdir}/jobs/examples/quick.ini",
                        "--output", str(tmp_path / "quick.h5")], capture_output=True, text=True,
                       env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    test = doctest.DocTestParser().get_doctest(session[0], {}, "python.md", "docs/python.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        runner.run(test)
    finally:
        os.chdir(cwd)
    result = runner.summarize(verbose=False)
    assert result.attempted >= 15 and result.failed == 0
