"""`python -m toothcontact` runs the console script."""

from .cli import app

app(prog_name="toothcontact")
