"""``python -m bearingsim`` runs the CLI."""

from .cli import main

main()
