"""The exit codes every command shares (a module of its own, so that the CLI reads them
without importing a command)."""

EXIT_OK, EXIT_FINDINGS, EXIT_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED = 0, 1, 2, 3, 130
