"""softplc check on a folder (runtime/check_summary.py, runtime/project/):
every source in it, one table with the POUs, whether they compiled, the
errors and warnings per file and POU, the frequent codes."""

from __future__ import annotations

from softplc.runtime.project import open_projects
from tests.test_cli import softplc


def _folder(tmp_path):
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "a.st").write_text(
        "FUNCTION_BLOCK A\nVAR_INPUT i : INT; END_VAR\ni := 1;\nEND_FUNCTION_BLOCK\n"  # W130: input assigned
        "PROGRAM Main\nVAR x : INT; END_VAR\nx := y;\nx := z;\nEND_PROGRAM\n"  # two E010
    )
    (tmp_path / "src" / "b.st").write_text("FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n")
    (tmp_path / ".git").mkdir()
    (tmp_path / ".git" / "junk.st").write_text("not ST")
    (tmp_path / "notes.txt").write_text("not a source")
    return tmp_path


def test_a_folder_is_its_sources(tmp_path):
    root = _folder(tmp_path)
    [project] = open_projects([str(root)])
    assert project.files == [str(root / "src" / "a.st"), str(root / "src" / "b.st")]


def test_check_on_a_folder_prints_the_table(tmp_path):
    root = _folder(tmp_path)
    r = softplc("check", root)
    assert r.returncode == 1
    table = r.stderr[r.stderr.index("file / POU") :].splitlines()
    assert table[0].split() == ["file", "/", "POU", "compiled", "errors", "libraries", "warnings"]
    # a.st: Main has the two errors and does not compile, A (a warning) does
    assert table[1].split() == ["src/a.st", "1/2", "2", "0", "1"]
    assert table[2].split() == ["A", "yes", "0", "0", "1"]
    assert table[3].split() == ["Main", "no", "2", "0", "0"]
    assert table[4].split() == ["src/b.st", "yes", "0", "0", "0"]
    assert table[5] == "total: 2 files, 3 POUs, 2 compiled (67 %); 2 errors; 1 warning"
    assert table[6] == "most frequent: E010 x2, W130 x1"
    assert r.stderr.rstrip().endswith("2 errors, 1 warning\nfor more on a code: softplc check --explain E010")


def test_an_empty_folder_is_a_usage_error(tmp_path):
    r = softplc("check", tmp_path)
    assert r.returncode == 2 and "no ST sources" in r.stderr


def test_an_error_names_the_profiles_that_accept_the_construct(tmp_path):
    f = tmp_path / "p.st"
    f.write_text("PROGRAM p\nVAR i : INT; w : WORD; END_VAR\nw := SHL(i, 1);\nx := 2;\nEND_PROGRAM\n")
    r = softplc("check", "--profile", "iec", f)
    assert r.returncode == 1
    shl, unknown = r.stderr.split("error E0")[1:3]
    # SHL of an INT: CODESYS shifts an integer's bits; IEC wants ANY_BIT
    assert "hint: the profiles codesys, twincat, schneider accept this (--profile codesys)" in shl
    assert "accept" not in unknown  # an unknown name is an error everywhere


def test_a_check_with_several_codes_ends_with_the_most_frequent(tmp_path):
    f = tmp_path / "p.st"
    f.write_text("PROGRAM p\nVAR i : INT; END_VAR\nx := 1;\ny := 2;\ni := 1.5;\nEND_PROGRAM\n")
    r = softplc("check", f)
    assert "most frequent: E010 x2, W121 x1" in r.stderr
