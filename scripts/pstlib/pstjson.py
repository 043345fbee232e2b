"""The provenance pst records in every JSON output (testbench/tool/reports/provenance.h): "schema",
"commit", "tool_versions", "command_line" at the top level. `pst regress -o` writes an object with
the runs under "runs" (schema 2); schema 1 files were the bare list of runs."""

KEYS = ("schema", "commit", "tool_versions", "command_line")


def regress_runs(doc):
    """The runs of a `pst regress -o` file, whichever schema; `doc` itself when it has none."""
    if isinstance(doc, dict) and isinstance(doc.get("runs"), list):
        return doc["runs"]
    return doc


def of(doc) -> dict:
    """The provenance keys of a pst JSON output ({} for a file without them)."""
    return {k: doc[k] for k in KEYS if k in doc} if isinstance(doc, dict) else {}
