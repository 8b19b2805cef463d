"""pytest configuration shared by the doctests and the test suite."""

# running __main__ would call the command line and exit
collect_ignore = ["linkage_sym/__main__.py"]
