#!/usr/bin/python3
"""Checks JSON files against a JSON Schema with python3-jsonschema (Debian).

usage: check_json_schema.py SCHEMA FILE...   exit 0 when every file is valid, 1 otherwise,
printing each problem as FILE: PATH: MESSAGE.
"""
import json
import sys

import jsonschema


def main(schema_path, files):
    with open(schema_path, encoding="utf-8") as schema_file:
        schema = json.load(schema_file)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    problems = 0
    for path in files:
        with open(path, encoding="utf-8") as document:
            instance = json.load(document)
        for error in validator.iter_errors(instance):
            where = "/".join(str(part) for part in error.absolute_path)
            print(f"{path}: /{where}: {error.message}")
            problems += 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2:]))
