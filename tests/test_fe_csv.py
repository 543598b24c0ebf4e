"""compare's CSV reader is the `[points] file` reader (pointfiles.csv_header and csv_values: one parse
into float64): an FE export's CSV, in the forms solvers and spreadsheets write, gives the numbers
Python's own float() reads from its text, the same the points reader gives; its faults are named by
data row, line and column; its decoded size is bounded before a value is parsed."""
import os

import numpy as np
import pytest

from stressfields import pointfiles
from stressfields.fe.formats import FormatProblem, read_csv, read_nodes

HEADER = ['"Node Label"', " X(mm)", "Y(mm) ", "Z(mm)", "S-S11 (N/mm^2)", "S-S33 (N/mm^2)", "S-S13 (N/mm^2)"]
ROWS = [["1001", "-5.7993e-02", " -0.058079", "0", "-300.7827554", "-838.75", "-251.26"],
        ["1002", "0.185127", "-1.1569E-2", "0.000", "153.5973332", "-0.7593161001", "8.852805381e-2"],
        ["1003", "+1.5", "0.25", "1e-3", "-1.0000000000000002", "2.2250738585072014e-308", "-0.0"]]


def _messy(path):
    """BOM, CRLF line ends, a comment block, a blank line, a quoted and spaced header, spaces around
    values, a trailing comment: what spreadsheets and FE post-processors write."""
    lines = ["# Abaqus report, step 1", "", ",".join(HEADER) + "  # units in parentheses"]
    lines += [",".join(r) for r in ROWS[:2]] + ["# increment 2", ",".join(ROWS[2])]
    path.write_bytes(b"\xef\xbb\xbf" + "\r\n".join(lines).encode() + b"\r\n")
    return path


def test_values_are_what_float_reads_and_what_the_points_reader_gives(tmp_path):
    path = _messy(tmp_path / "abaqus.csv")
    table = read_csv(path)
    names = [c.name for c in table.columns]
    assert names == ["node", "x", "y", "z", "sigma_xx", "sigma_zz", "sigma_xz"]
    assert [c.unit for c in table.columns] == [None, "mm", "mm", "mm", "N/mm^2", "N/mm^2", "N/mm^2"]
    expected = np.array([[float(v) for v in row] for row in ROWS])
    got = np.stack([c.values for c in table.columns], axis=1)
    assert got.dtype == np.float64 and got.tobytes() == expected.tobytes()     # -0.0 and the subnormal too
    points = pointfiles.csv_columns(path.read_bytes())
    assert [c.label for c in points] == [h.strip().strip('"') for h in HEADER]
    for mine, theirs in zip(table.columns, points):
        assert mine.values.tobytes() == theirs.values.tobytes()
    # read through the entry point, by a symbolic link (the reader itself follows none)
    link = tmp_path / "link.csv"
    os.symlink(path, link)
    again = read_nodes(link)[0].columns
    assert all(a.values.tobytes() == b.values.tobytes() for a, b in zip(again, table.columns))


@pytest.mark.parametrize("body, words", [
    ("x,sigma_xx\n0,1\n1,nan\n", "data row 1 (from 0), column 'sigma_xx': NaN"),
    ("x,sigma_xx\n0,1\n\n# c\n1,2,3\n", "data row 1 (from 0, line 5) has 3 values but the header names 2 columns"),
    ("x,sigma_xx\n0,1\n2,1.0.0\n", "data row 1 (from 0, line 3), column 'sigma_xx': not a number"),
    ("x,sigma_xx,\n0,1,2\n", "has an empty column name (column 3)"),
    ("x,S-S11 (N/mm^2),x y z\n0,1,2\n", f"column 3 (from 1) of the header is not {pointfiles.LABEL_RULE}"),
    ("0,1\n2,3\n", "holds numbers; the first line must name the columns"),
    ("# only a comment\n\n", "no header line"),
])
def test_faults_are_named_by_row_line_and_column(tmp_path, body, words):
    path = tmp_path / "bad.csv"
    path.write_text(body)
    with pytest.raises(FormatProblem) as err:
        read_csv(path)
    assert words in str(err.value) and "\n" not in str(err.value)


def test_decoded_size_is_bounded_before_parsing(tmp_path, monkeypatch):
    """Ten rows of two numbers, eleven line ends counted (the last line may lack one): a limit of 159
    bytes refuses them from the line count, before a value is read. Where the body's size alone bounds
    the decoded size (4 bytes per byte of the body: a row of k numbers takes at least 2k bytes) no
    line is counted and the rows are parsed."""
    path = tmp_path / "ten.csv"
    path.write_text("x,sigma_xx\n" + "".join(f"{i},{i}\n" for i in range(10)))
    parsed = []
    real = pointfiles._csv_values
    monkeypatch.setattr(pointfiles, "_csv_values", lambda *a, **k: parsed.append(1) or real(*a, **k))
    monkeypatch.setattr(pointfiles, "MAX_DECODED_BYTES", 159)
    with pytest.raises(FormatProblem, match="its 2 columns of 11 rows decode to 176 bytes; at most 159"):
        read_csv(path)
    assert parsed == []
    monkeypatch.setattr(pointfiles, "MAX_DECODED_BYTES", 4 * (path.stat().st_size - len("x,sigma_xx\n") + 1))
    assert read_csv(path).columns[1].values.tolist() == list(map(float, range(10)))
    assert parsed == [1]
