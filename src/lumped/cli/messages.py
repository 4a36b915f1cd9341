"""An API error in the command line's words: the API's argument names and the options they are.

The API's ``ValueError`` messages begin with the argument's name
(``"force_amplitude: ..."``); :func:`option_message` writes that name as the
option (``"--force-amplitude: ..."``).
"""

from __future__ import annotations

import re

from lumped.drivers.methods import OPTIONS
from lumped.model.parameters import PARAMETERS

#: The API's argument names (what its ``ValueError`` messages begin with) -> options; the
#: options that set the system, its motion and the grid (their defaults, help and checks)
#: are those of :data:`lumped.model.parameters.PARAMETERS`.
API_TO_OPTION = (
    {name: p.option for name, p in PARAMETERS.items()}
    | {
        "t_end/dt": "--t-end/--dt",
        "vary": "--vary",
        "periods": "--periods",
        "method": "--method",
    }
    | {name: option.flag for name, (option, _) in OPTIONS.items()}
)
LEADING_NAME = re.compile(r"^([a-z][a-z0-9_/]*)(?=:| must)")


def option_message(message: str) -> str:
    """An API error message in the command line's words.

    The API's messages begin with the argument's name followed by ``:`` or
    `` must`` (``"force_amplitude: ..."``); that name becomes the option
    (``"--force-amplitude: ..."``).  Only the leading name is replaced: the
    rest may be a formula or echo the user's value.  A message that does not
    begin with an argument name is returned unchanged.

    Parameters
    ----------
    message : str
        The text of a ``ValueError`` raised by :mod:`lumped`.

    Returns
    -------
    str
    """
    lead = LEADING_NAME.match(message)
    if lead is None or lead.group(1) not in API_TO_OPTION:
        return message
    return API_TO_OPTION[lead.group(1)] + message[lead.end() :]
