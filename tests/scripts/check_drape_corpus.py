#!/usr/bin/python3
"""Runs scripts/drape-corpus on the given mold files and checks what it writes:

- it exits 0 and writes OUTDIR/campaign.csv and OUTDIR/summary.txt;
- the CSV has the documented columns (docs/corpus-campaign.md) and every row all of them;
  every row names one of the given files, a face index (or `all` for a shell, nothing for a
  file that could not be listed) and a verdict of the documented set;
- a drape's row agrees with its report.json (OUTDIR/faces/...): status and node counts;
- every verdict follows from the row's own figures by the documented rules (first cause that
  applies, the causes listed in order), e.g. a clean row has no failed, conflict or
  shear-limit node, an ok report, a cut outline covering at least 98 % and one piece;
- the summary has one line per file and an overall line; each line's counts add up to its
  number of drapes, and they are the CSV's counts of that file's rows (overall: all rows);
- with --expect-files N: N files in the summary; with --expect-verdict NAME=VERDICT: every
  row of the file named NAME has that verdict (a file that cannot be read, a timeout).

usage: check_drape_corpus.py --plyfit BIN --out DIR [--expect-files N]
                             [--expect-verdict NAME=VERDICT ...] -- [drape-corpus arguments]
Exit 0 when every check passes, 1 with a line per failed check.
"""
import argparse
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "drape-corpus")
COLUMNS = ("file face kind degrees rational area_mm2 spacing status mapped outside failed "
           "failed_reasons shear_limit conflict conflict_reasons overlap path_end max_shear_deg "
           "coverage_pct outline_coverage_pct cell_coverage_pct pieces holes single_cell_loops "
           "seconds verdict causes note").split()
VERDICTS = ["error", "timeout", "failed", "conflict", "shear_stop_no_lock", "under_98", "pieces",
            "partial", "clean"]
SUMMARY_WORDS = {"error": "error", "timeout": "timeout", "failed": "failed",
                 "conflict": "conflict", "shear_stop_no_lock": "shear stop without lock",
                 "under_98": "cut outline under 98 %", "pieces": "cut in pieces",
                 "partial": "partial", "clean": "clean"}
problems = []


def check(ok, what):
    if not ok:
        problems.append(what)
    return ok


def expected_causes(r):
    """The causes the documented rules give for a row of a drape that ran."""
    c = []
    if int(r["failed"]) > 0:
        c.append("failed")
    if int(r["conflict"]) > 0:
        c.append("conflict")
    if int(r["shear_limit"]) > 0:
        c.append("shear_stop_no_lock")
    if float(r["coverage_pct"]) < 98.0:
        c.append("under_98")
    if int(r["pieces"]) > 1:
        c.append("pieces")
    if r["status"] != "ok" and not c:
        c.append("partial")
    return c or ["clean"]


def check_drape_row(r, out):
    where = f"{r['file']} face {r['face']}"
    for k in ("area_mm2", "spacing", "max_shear_deg", "coverage_pct", "outline_coverage_pct",
              "cell_coverage_pct", "seconds"):
        check(math.isfinite(float(r[k])), f"{where}: {k} {r[k]!r} is not a finite number")
    check(float(r["spacing"]) > 0, f"{where}: spacing {r['spacing']} is not positive")
    c = expected_causes(r)
    check(r["causes"] == ";".join(c), f"{where}: causes {r['causes']!r}, the rules give {c}")
    check(r["verdict"] == c[0], f"{where}: verdict {r['verdict']!r}, the rules give {c[0]!r}")
    if r["verdict"] == "clean":
        check(r["status"] == "ok" and int(r["failed"]) == 0 and int(r["shear_limit"]) == 0,
              f"{where}: clean but status {r['status']}, failed {r['failed']}")
    name = "shell" if r["face"] == "all" else f"face-{r['face']}"
    # The campaign's folder of a file: its name with other characters than [A-Za-z0-9._-] as _.
    folder = re.sub(r"[^A-Za-z0-9._-]", "_", os.path.basename(r["file"]))
    report = os.path.join(out, "faces", folder, name, "report.json")
    if not check(os.path.isfile(report), f"{where}: no {report}"):
        return
    with open(report) as f:
        rep = json.load(f)
    nodes = rep["nodes"]
    check(rep["status"] == r["status"], f"{where}: status {r['status']} vs report {rep['status']}")
    for k in ("mapped", "outside", "failed", "shear_limit", "conflict", "overlap", "path_end"):
        check(int(r[k]) == nodes[k], f"{where}: {k} {r[k]} vs report.json {nodes[k]}")
    check(sum(nodes["failed_reasons"].values()) == nodes["failed"],
          f"{where}: failed reasons do not add up in report.json")


def check_summary(rows, lines, expect_files):
    by_label = {}
    for line in lines:
        m = re.match(r"^(.*): (\d+) drapes: (.*)$", line)
        if not check(m is not None, f"summary line not of the documented form: {line!r}"):
            continue
        counts = {}
        for part in m.group(3).split(", "):
            pm = re.match(r"^(\d+) (.*)$", part)
            if check(pm is not None, f"summary part {part!r} has no count"):
                counts[pm.group(2)] = int(pm.group(1))
        check(list(counts) == [SUMMARY_WORDS[v] for v in VERDICTS],
              f"summary line {line!r} does not list the verdicts in order")
        check(sum(counts.values()) == int(m.group(2)),
              f"summary line {line!r}: the counts add up to {sum(counts.values())}")
        by_label[m.group(1)] = (int(m.group(2)), counts)
    check(list(by_label)[-1:] == ["overall"], "the summary's last line is not the overall line")
    labels = [k for k in by_label if k != "overall"]
    check(sorted(labels) == sorted(set(r["file"] for r in rows)),
          f"summary files {labels} are not the CSV's files")
    if expect_files is not None:
        check(len(labels) == expect_files, f"{len(labels)} files summarised, {expect_files} given")
    for label, (n, counts) in by_label.items():
        mine = [r for r in rows if label == "overall" or r["file"] == label]
        check(n == len(mine), f"summary {label}: {n} drapes, the CSV has {len(mine)} rows")
        for v in VERDICTS:
            k = sum(1 for r in mine if r["verdict"] == v)
            check(counts.get(SUMMARY_WORDS[v]) == k,
                  f"summary {label}: {counts.get(SUMMARY_WORDS[v])} {v}, the CSV has {k}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plyfit", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--expect-verdict", action="append", default=[])
    ap.add_argument("--expect-files", type=int)
    ap.add_argument("rest", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    rest = a.rest[1:] if a.rest[:1] == ["--"] else a.rest
    shutil.rmtree(a.out, ignore_errors=True)
    p = subprocess.run([sys.executable, SCRIPT, "--plyfit", a.plyfit, "-o", a.out, "--quiet"]
                       + rest, capture_output=True, text=True)
    if not check(p.returncode == 0, f"drape-corpus exited {p.returncode}: {p.stderr.strip()}"):
        print("\n".join(problems))
        return 1
    with open(os.path.join(a.out, "campaign.csv"), newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        raw = list(reader)
    check(header == COLUMNS, f"CSV header {header} is not the documented one")
    rows = []
    for k, fields in enumerate(raw):
        if check(len(fields) == len(header), f"CSV row {k + 2} has {len(fields)} fields"):
            rows.append(dict(zip(header, fields)))
    check(len(rows) > 0, "the CSV has no row")
    for r in rows:
        check(r["verdict"] in VERDICTS, f"{r['file']} face {r['face']}: verdict {r['verdict']!r}")
        check(re.fullmatch(r"\d+|all|", r["face"]) is not None, f"face {r['face']!r}")
        if r["verdict"] in ("error", "timeout"):
            check(r["note"] != "", f"{r['file']} face {r['face']}: {r['verdict']} without a note")
        else:
            check_drape_row(r, a.out)
    with open(os.path.join(a.out, "summary.txt")) as f:
        lines = f.read().splitlines()
    check(lines == p.stdout.splitlines(), "summary.txt is not what drape-corpus printed")
    check_summary(rows, lines, a.expect_files)
    for e in a.expect_verdict:
        name, verdict = e.split("=", 1)
        mine = [r for r in rows if os.path.basename(r["file"]) == name]
        check(len(mine) > 0 and all(r["verdict"] == verdict for r in mine),
              f"{name}: verdicts {[r['verdict'] for r in mine]}, expected all {verdict}")
    print("\n".join(problems) if problems else f"drape-corpus: {len(rows)} rows checked")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
