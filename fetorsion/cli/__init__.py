"""The command line, ``fetorsion <command> ...``: parses and checks every option before any
work, calls the stages, prints their tables. User mistakes print one message, exit 2.
"""

from .commands import build_parser, main
from .process import console

__all__ = ["build_parser", "console", "main"]
