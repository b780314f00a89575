"""``python -m exofric`` runs the CLI."""

from .cli import main

main()
