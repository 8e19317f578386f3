"""The command-line interface ``cdpr``: one module per command; shared helpers in :mod:`.common`."""
