"""Errors raised on bad input: each names the field at fault and the problem."""


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
