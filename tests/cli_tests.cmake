# Tests of globular_cli.
