"""Exceptions and warnings of fretwear.

Every error names the culprit (a column, a keyword, a row, a file) and says how to fix it.
Every warning is a subclass of :class:`FretwearWarning` so users can filter them as a family.
"""

from __future__ import annotations


class FretwearError(Exception):
    """Base class of all fretwear errors."""


class InputError(FretwearError, ValueError):
    """Bad user input: a missing or malformed column, keyword, value or file."""


class HistoryError(InputError):
    """A contact history is invalid (length, NaN, non-increasing time, negative force ...)."""


class FormatError(InputError):
    """A file cannot be read in the format asked for or guessed."""


class KeywordError(InputError):
    """A keyword is missing, unknown, or excluded by another one (Code_Aster catalogue rules)."""


class DatabaseError(InputError):
    """A coefficient is not in the database (unknown pair, empty box)."""


class MissingDependencyError(FretwearError, ImportError):
    """An optional package is not installed (or cannot be imported); the message names the
    extra that installs it (``pip install 'fretwear[formats]'``). See :mod:`fretwear._optional`."""


class StabilityError(FretwearError, ValueError):
    """A time step is too large for the explicit scheme to be stable."""


class FretwearWarning(UserWarning):
    """Base class of all fretwear warnings."""


class StationarityWarning(FretwearWarning):
    """The block powers spread more than the user's threshold: the power is not stationary."""


class RangeWarning(FretwearWarning):
    """A value lies beyond a relation's range of validity; the result there is NaN."""


class UnusedKeywordWarning(FretwearWarning):
    """A keyword was given that the chosen model or contact type does not use."""


class LawWarning(FretwearWarning):
    """A wear law is used outside its usual regime (e.g. EDF_MZ with S > A·P^b)."""


class ConfidenceWarning(FretwearWarning):
    """A confidence interval rests on too few samples or on correlated ones (too narrow)."""


class UnitsWarning(FretwearWarning):
    """A history's values are implausible in SI units (a file exported in mm, ms, mN or kN);
    the message names the channel, the value, the likely unit and the ``units`` option."""


class ResolutionWarning(FretwearWarning):
    """A history's sampling is too coarse for what it records: its impacts last only a few
    samples, so the wear power computed from the samples is off (docs/code_aster.md §5)."""


class WholeReadWarning(FretwearWarning):
    """A large file is read whole while streaming was asked: its format cannot be streamed
    (NPZ, Code_Aster text); the message says how to convert it."""


class PerforationWarning(FretwearWarning):
    """The mobile's worn depth passed the perforation criterion (PERCEMENT × wall thickness)."""
