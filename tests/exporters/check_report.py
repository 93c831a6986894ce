"""The verdict of a check_*.py script: its first failures and their count, or a one-line ok."""


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
