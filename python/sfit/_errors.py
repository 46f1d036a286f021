"""sfit.Error: the one exception of sfit (the C++ sfit::Error, docs/errors.md)."""


class Error(ValueError):
    """Bad input or a failed fit, as the CLI reports it.

    str(error) is the CLI's one-line message ("file:line:column: message",
    "option: message" or "row 3, point 7: message").

    Attributes:
        code: the stable name of the error ("usage", "input-unreadable",
            "input-syntax", "input-data", "output-write", "tolerance-not-met",
            "internal", "cancelled").
        exit_code: the CLI's exit code for it (2 ... 9).
        message: the bare message, without the place.
        file, line, column: where in an input file (None if unknown).
        row, index: the 0-based row and point in it (None if unknown).
        option: the keyword argument concerned (None if none).
        values: the offending numbers.
        fit: for "tolerance-not-met" after a finished fit, that sfit.Fit.
    """

    def __init__(self, text, code="internal", exit_code=8, message=None, file=None, line=None,
                 column=None, row=None, index=None, option=None, values=()):
        super().__init__(text)
        self.code = code
        self.exit_code = exit_code
        self.message = text if message is None else message
        self.file = file
        self.line = line
        self.column = column
        self.row = row
        self.index = index
        self.option = option
        self.values = tuple(values)
        self.fit = None
