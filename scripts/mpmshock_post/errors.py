"""The one exception the post-processing tools raise for bad input or unreadable runs.

The command line turns it into a one-line message and a non-zero exit; a notebook sees it as an
ordinary exception whose text says what was wrong and what would be valid.
"""


class PostError(Exception):
    """A run directory, snapshot or request that cannot be honoured, with the reason."""
