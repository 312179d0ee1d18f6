"""Subcommands of the ``rigidkin`` command line, one module each (``register(subparsers)``)."""
