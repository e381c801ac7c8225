#!/usr/bin/env python3
"""Validate TOML files against a JSON Schema with an independent validator.

Usage: schema_check.py SCHEMA.json FILE.toml [FILE.toml ...]

Each TOML file is read with Python's tomllib, as JSON data, and validated with `jsonschema`
(Draft 2020-12, the draft `solsim schema` emits). Prints one JSON object per file on stdout:
{"file": ..., "valid": bool, "errors": ["<path>: <message>", ...]}. Exit 0 whatever the
verdicts (the caller judges them); 2 on a usage error or a file that is not TOML.
Needs jsonschema (peers/requirements.txt); peers/.venv is created on first use.
"""
import json
import sys
import tomllib

from peer_common import ensure_venv


def main():
    ensure_venv("jsonschema")
    import jsonschema

    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    with open(sys.argv[1], encoding="utf-8") as f:
        schema = json.load(f)
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    validator = cls(schema)
    for path in sys.argv[2:]:
        try:
            with open(path, "rb") as f:
                data = tomllib.load(f)
        except tomllib.TOMLDecodeError as e:
            print(f"{path}: not TOML: {e}", file=sys.stderr)
            sys.exit(2)
        errors = sorted(
            f"{'/'.join(str(p) for p in e.absolute_path) or '(top)'}: {e.message}"
            for e in validator.iter_errors(data)
        )
        print(json.dumps({"file": path, "valid": not errors, "errors": errors}))


if __name__ == "__main__":
    main()
