"""The command line: exit codes, files written, robustness, centres."""
