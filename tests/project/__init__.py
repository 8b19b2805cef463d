"""The repository as a whole: architecture contracts, the README's commands."""
