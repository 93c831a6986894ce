"""What the check_*.py scripts share: the file checked with report.json beside it, a list of
failures, and the verdict: the first failures and their count, or a one-line ok."""
import json
import os


class Case:
    """DIR/`name` (path), DIR/report.json (report) and the failures found (check() adds one)."""

    def __init__(self, d, name):
        self.path = os.path.join(d, name)
        with open(os.path.join(d, "report.json"), encoding="utf-8") as f:
            self.report = json.load(f)
        self.failures = []

    def check(self, ok, what):
        if not ok:
            self.failures.append(what)



def finish(tool, path, failures, summary):
    """Prints the first 20 failures and their count (returns exit status 1), or "ok (summary)"
    (returns 0)."""
    if failures:
        for f in failures[:20]:
            print("%s: %s: %s" % (tool, path, f))
        print("%s: %d failures" % (tool, len(failures)))
        return 1
    print("%s: %s: ok (%s)" % (tool, path, summary))
    return 0
