#!/usr/bin/env python3
"""Writes the lab-format fixtures of tests/app/lab_files.rs and python/tests/test_lab.py from one
readings sheet (tests/data/lab/utf8/soil_b3.csv, written here too): the same sheet as a
spreadsheet would export or keep it.

    tests/data/lab/utf8/soil_b3.csv    UTF-8, comma-separated, decimal point, LF
    tests/data/lab/latin1/soil_b3.csv  Windows-1252 (Latin-1), semicolons, decimal comma, CRLF,
                                       the trailing semicolons Excel writes after a `#` line
    tests/data/lab/bom/soil_b3.csv     UTF-8 with BOM, semicolons, decimal comma, CRLF
    tests/data/lab/xlsx/soil_b3.xlsx   one row per line, one cell per field, numbers as numbers
    tests/data/lab/ods/soil_b3.ods     the same as OpenDocument
    tests/data/lab/kv/soil_b3.xlsx     the figures as key/value cells (`# dry_mass_g` | 48.797)
    tests/data/lab/bad/*.xlsx, *.ods   the sheet with one mistake each (tests/app/bad_lab_inputs.rs)

Needs openpyxl and odfpy (pip install openpyxl odfpy). Run from the repository's root:
python3 scripts/make_lab_fixtures.py
"""
import os

FIGURES = [
    ("standard", "d7928"),
    ("hydrometer", "152H"),
    ("sample", "clay loam B3"),
    ("note", "bath at 21.5 °C, dispersant 5 g/L"),
    ("dry_mass_g", 48.797),
    ("specific_gravity", 2.7),
    ("meniscus_correction", 1.0),
    ("h_r1_cm", 20.3),
    ("h_r2_cm", 8.6),
    ("bulb_volume_ml", 55),
    ("cylinder_area_cm2", 26.1),
]
HEADER = ["time_min", "reading", "temperature_c", "blank_reading"]
ROWS = [
    [1, 44.5, 21.5, 6.25],
    [2, 40.0, 21.5, 6.25],
    [4, 35.5, 21.5, 6.25],
    [15, 28.0, 21.6, 6.25],
    [30, 24.5, 21.6, 6.25],
    [60, 21.0, 21.8, 6.5],
    [240, 16.5, 22.0, 6.5],
    [1440, 12.0, 21.5, 6.25],
]
ROOT = "tests/data/lab"


def text(x, comma=False):
    s = repr(x) if isinstance(x, float) else str(x)
    return s.replace(".", ",") if comma and isinstance(x, float) else s


def csv(delim, comma, pad):
    lines = []
    for k, v in FIGURES:
        v = text(v, comma) if not isinstance(v, str) else v
        lines.append(f"# {k} = {v}" + (delim * (len(HEADER) - 1) if pad else ""))
    lines.append(delim.join(HEADER))
    for r in ROWS:
        lines.append(delim.join(text(x, comma) for x in r))
    return lines


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def main():
    write(f"{ROOT}/utf8/soil_b3.csv", ("\n".join(csv(",", False, False)) + "\n").encode("utf-8"))
    write(
        f"{ROOT}/latin1/soil_b3.csv",
        ("\r\n".join(csv(";", True, True)) + "\r\n").encode("cp1252"),
    )
    write(
        f"{ROOT}/bom/soil_b3.csv",
        ("\r\n".join(csv(";", True, False)) + "\r\n").encode("utf-8-sig"),
    )

    import openpyxl

    for layout in ("xlsx", "kv"):
        wb = openpyxl.Workbook()
        ws = wb.active
        ws.title = "Sheet1"
        for k, v in FIGURES:
            ws.append([f"# {k} = {v}"] if layout == "xlsx" else [f"# {k}", v])
        ws.append(HEADER)
        for r in ROWS:
            ws.append(r)
        os.makedirs(f"{ROOT}/{layout}", exist_ok=True)
        wb.save(f"{ROOT}/{layout}/soil_b3.xlsx")

    from odf.opendocument import OpenDocumentSpreadsheet
    from odf.table import Table, TableRow, TableCell
    from odf.text import P

    doc = OpenDocumentSpreadsheet()
    table = Table(name="Sheet1")

    def row(cells):
        tr = TableRow()
        for c in cells:
            if isinstance(c, str):
                tc = TableCell(valuetype="string")
            else:
                tc = TableCell(valuetype="float", value=c)
            tc.addElement(P(text=str(c)))
            tr.addElement(tc)
        table.addElement(tr)

    for k, v in FIGURES:
        row([f"# {k} = {v}"])
    row(HEADER)
    for r in ROWS:
        row(r)
    doc.spreadsheet.addElement(table)
    os.makedirs(f"{ROOT}/ods", exist_ok=True)
    doc.save(f"{ROOT}/ods/soil_b3.ods")

    bad_workbooks()


def sheet(figures=FIGURES, header=HEADER, rows=ROWS):
    import openpyxl

    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Sheet1"
    for k, v in figures:
        ws.append([f"# {k} = {v}"])
    ws.append(header)
    for r in rows:
        ws.append(r)
    return wb


def bad_workbooks():
    """One mistake per workbook; the row of the readings is 12 + n (11 figure lines, the
    header on row 12)."""
    import datetime

    os.makedirs(f"{ROOT}/bad", exist_ok=True)
    rows = [list(r) for r in ROWS]
    rows[2][1] = "forty"  # B15
    sheet(rows=rows).save(f"{ROOT}/bad/text_reading.xlsx")
    rows = [list(r) for r in ROWS]
    rows[0][1] = "44,5"  # B13: a decimal comma in a text cell
    sheet(rows=rows).save(f"{ROOT}/bad/comma_text.xlsx")
    rows = [list(r) for r in ROWS]
    rows[1][0] = datetime.time(0, 2, 0)  # A14: a clock time
    sheet(rows=rows).save(f"{ROOT}/bad/time_cell.xlsx")
    figures = list(FIGURES)
    figures[4] = ("dry_mas_g", 48.797)  # A5: a typo in a key
    sheet(figures=figures).save(f"{ROOT}/bad/unknown_key.xlsx")
    header = ["time_s"] + HEADER[1:]  # minutes under time_s: A13
    sheet(header=header).save(f"{ROOT}/bad/minutes_as_seconds.xlsx")
    rows = [list(r) for r in ROWS]
    for r in rows:
        r[2] = 70.7  # C13: °F
    sheet(rows=rows).save(f"{ROOT}/bad/fahrenheit.xlsx")
    figures = list(FIGURES)
    figures[5] = ("specific_gravity", 2700)  # A6: a density in kg/m3
    sheet(figures=figures).save(f"{ROOT}/bad/density_for_gs.xlsx")
    rows = [list(r) for r in ROWS]
    rows[3][1] = 99  # B16: off the 152H's scale
    sheet(rows=rows).save(f"{ROOT}/bad/off_scale.xlsx")


if __name__ == "__main__":
    main()
