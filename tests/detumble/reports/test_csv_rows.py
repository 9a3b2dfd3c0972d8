"""FastCsvWriter writes every row byte for byte as ``csv.writer(f, lineterminator="\\n")`` does (CSVROW-*)."""

from __future__ import annotations

import csv
import io
import math
import random

from detumble.reports.csv_rows import FastCsvWriter, FormattedCsvWriter

_WORDS = ["", "BDOT", "IDLE", "a,b", 'say "hi"', "two\nlines", "cr\rhere", "None", "x None y", " spaced ",
          "nan", "0.5000", "é", "tab\there"]


def _both(rows) -> tuple[str, str]:
    fast, ref = io.StringIO(), io.StringIO()
    writer, reference = FastCsvWriter(fast), csv.writer(ref, lineterminator="\n")
    for row in rows:
        writer.writerow(row)
        reference.writerow(row)
    return fast.getvalue(), ref.getvalue()


def _value(rng: random.Random):
    kind = rng.randrange(8)
    if kind == 0:
        return rng.choice(_WORDS)
    if kind == 1:
        return rng.choice([0.0, -0.0, math.nan, math.inf, -math.inf, 1e-300, 5e-324, 1e22])
    if kind == 2:
        return rng.randrange(-300, 300)
    if kind == 3:
        return rng.choice([None, True, False])
    if kind == 4:
        return f"{rng.uniform(-100, 100):.4f}"
    return rng.uniform(-1.0, 1.0) * 10.0 ** rng.randrange(-12, 12)


def test_csvrow_001_random_rows_as_the_csv_module_writes_them():
    rng = random.Random(20261204)
    rows = [[_value(rng) for _ in range(rng.randrange(0, 70))] for _ in range(3000)]
    fast, ref = _both(rows)
    assert fast == ref


def test_csvrow_002_the_rows_csv_writes_specially():
    rows = [[""], [None], [], ["", ""], [None, 1.5], ["a,b", 1.0], ['q"', 2], ["l\nf"], ["c\rr", 0.0],
            ["None"], [1.0, "None"], [1.5, 2.5, -0.0, math.nan], ("tuple", 3), [True, False]]
    fast, ref = _both(rows)
    assert fast.splitlines() == ref.splitlines()
    assert fast == ref


def test_csvrow_003_a_report_row_takes_the_fast_path():
    """A row of the kind the run reports write (floats, fixed-point text, an enum name, empty cells)
    is written by the join, not handed to the csv module."""
    out = io.StringIO()
    writer = FastCsvWriter(out)

    class Refuse:
        def writerow(self, row):
            raise AssertionError(f"handed to the csv module: {row!r}")

    writer._csv = Refuse()  # type: ignore[assignment]
    row = ["1.000000", 11.083847526465805, -3.0796131486843206, "80.000", "", "BDOT", 0.0, -0.0, 5.7e-11, 0]
    writer.writerow(row)
    assert out.getvalue() == "1.000000,11.083847526465805,-3.0796131486843206,80.000,,BDOT,0.0,-0.0,5.7e-11,0\n"


def test_formatted_rows_are_the_f_strings_bytes():
    """OUT-010: :class:`FormattedCsvWriter` given raw numbers writes what ``csv.writer`` writes of the row
    formatted with f-strings (floats, ints, bools, nan/inf, -0.0 in formatted columns; texts — the header,
    empty cells, ``"nan"`` — and unformatted columns as they are; a row longer than the formats)."""
    rng = random.Random(20261205)
    specs = (".6f", None, ".3f", ".4f", None, ".4f")
    numbers = [0.0, -0.0, math.nan, math.inf, -math.inf, 1e-300, 5e-324, 1e22, 0.00005, -0.00005, 2.5, 7, -3,
               True, False]
    rows = [["t_s", "a", "b", "c", "d", "e"], ["", "", "", "", "", ""], ["nan"] * 6]
    for _ in range(2000):
        rows.append([rng.choice(numbers) if rng.random() < 0.3 else rng.uniform(-1e3, 1e3)
                     for _ in range(rng.randrange(1, 9))])
    out, ref = io.StringIO(), io.StringIO()
    writer, reference = FormattedCsvWriter(out, specs), csv.writer(ref, lineterminator="\n")
    for row in rows:
        writer.writerow(row)
        padded = specs + (None,) * max(0, len(row) - len(specs))
        reference.writerow([v if s is None or isinstance(v, str) else f"{v:{s}}"
                            for v, s in zip(row, padded, strict=False)])
    assert out.getvalue() == ref.getvalue()
    one = io.StringIO()
    FormattedCsvWriter(one, specs).writerow([1.5, 0.1, 2, "", "IDLE", 1 / 3, 0.25])
    assert one.getvalue() == "1.500000,0.1,2.000,,IDLE,0.3333,0.25\n"
