"""Errors raised on bad input: each names the field at fault and the problem; the largest magnitude a number of
the input may have."""

MAX_MAGNITUDE = 1e100  # robot and command-line numbers beyond this would overflow double precision in squares and
# products of them (a load of 1e300 gave residual inf; lengths of 1e308 an 'oo' in exported equations)


def check_magnitude(x: float, field: str) -> None:
    """A :class:`CdprInputError` naming ``field`` when |x| > :data:`MAX_MAGNITUDE`."""
    if abs(x) > MAX_MAGNITUDE:
        raise CdprInputError(field, f"{x:g} is beyond {MAX_MAGNITUDE:g}: squares and products of such numbers "
                                    f"overflow double precision (choose other units)")


class CdprInputError(ValueError):
    """Bad input. ``field`` names the offending field (e.g. ``base[2]``), ``problem`` says what is wrong.

    ``str(err)`` is one line meant for a person: ``"<source>: field 'base[2]': expected 3 numbers, got 2"``.
    """

    def __init__(self, field: str, problem: str, source: str | None = None):
        self.field = field
        self.problem = problem
        self.source = source
        where = f"{source}: " if source else ""
        super().__init__(f"{where}field '{field}': {problem}")

    def with_source(self, source: str) -> "CdprInputError":
        return CdprInputError(self.field, self.problem, source)


def reject_unknown_keys(data, allowed, where: str = "") -> None:
    """A :class:`CdprInputError` when the mapping ``data`` has keys outside ``allowed`` (a misspelt key must not be
    ignored: that would change the meaning of the input).  The field is the path of the first unknown key (``where``
    + ``.`` + key, or the key at the top level); the problem lists every unknown key and the allowed ones."""
    extra = [k for k in data if k not in allowed]
    if extra:
        field = f"{where}.{extra[0]}" if where else str(extra[0])
        raise CdprInputError(field, f"unknown key{'s' if len(extra) > 1 else ''} {', '.join(map(repr, extra))} "
                                    f"(allowed keys: {', '.join(allowed)})")
