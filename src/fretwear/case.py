"""Deprecated: TOML case files moved to :mod:`fretwear.workflows.case_files`."""

import warnings

from fretwear.workflows.case_files import *  # noqa: F401,F403
from fretwear.workflows.case_files import (  # noqa: F401
    FOREIGN_SECTIONS,
    KEYS,
    TIME_UNITS,
    CaseResult,
    case_arguments,
    check_keys,
    chunked_power,
    keys_help,
    keyword_hint,
    load_case,
    read_case_toml,
    run_case,
    validate_case,
)

warnings.warn("fretwear.case is deprecated: import from fretwear.workflows.case_files",
              DeprecationWarning, stacklevel=2)
