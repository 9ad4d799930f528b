"""The package's private floor: argument checks, size limits, progress reporting and the base
of the configuration tables. Nothing here is public API."""
