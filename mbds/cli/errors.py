"""How the command-line tools report bad input: ``file:line: message`` and exit code 2."""

from __future__ import annotations

import contextlib
import sys
import traceback
import warnings

import typer

from mbds.errors import ModelError, ModelWarning

EXIT_BAD_INPUT = 2


def _show_warning(message, category, filename, lineno, file=None, line=None):
    if issubclass(category, ModelWarning):
        print(f"warning: {message}", file=sys.stderr)
    else:
        print(warnings.formatwarning(message, category, filename, lineno, line), file=sys.stderr, end="")


@contextlib.contextmanager
def reported_errors(debug: bool):
    """Run a command: model warnings go to stderr as ``warning: file:line: ...``; a
    :class:`ModelError` prints ``file:line: message`` and exits with code 2 (with the
    traceback too when ``debug``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("always", ModelWarning)
        warnings.showwarning = _show_warning
        try:
            yield
        except ModelError as exc:
            if debug:
                traceback.print_exc()
            print(f"error: {exc}", file=sys.stderr)
            raise typer.Exit(EXIT_BAD_INPUT) from None
