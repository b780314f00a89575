"""``python -m exofric`` runs the CLI."""

from exofric.cli import main

main()
