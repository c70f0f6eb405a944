"""The one exception the post-processing tools raise for bad input or unreadable runs.

The command line turns it into a one-line message and a non-zero exit; a notebook sees it as an
ordinary exception whose text says what was wrong and what would be valid.
"""


class PostError(Exception):
    """A run directory, snapshot or request that cannot be honoured, with the reason."""


def argument_type(parse):
    """An argparse type from a parser that raises PostError or ValueError, so that bad values are
    usage errors (exit 2) with the parser's message."""
    import argparse

    def convert(text):
        try:
            return parse(text)
        except (PostError, ValueError) as e:
            raise argparse.ArgumentTypeError(str(e)) from None
    convert.__name__ = parse.__name__
    return convert


def select_named(series, names, path, what):
    """The named entries of a CSV's per-name series (all of them when `names` is empty); `what` is
    the singular noun ('region', 'probe') for the messages."""
    if not series:
        raise PostError(f"{path} has no rows yet")
    if not names:
        return series
    unknown = [name for name in names if name not in series]
    if unknown:
        raise PostError(f"no {what} {', '.join(repr(n) for n in unknown)} in {path} ({what}s: {', '.join(series)})")
    return {name: series[name] for name in names}
