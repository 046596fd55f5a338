"""A ``DesignReport`` <-> nested tuples of strings, numbers, booleans and None, exactly (the
result cache stores them with ``marshal``, which keeps tuples as tuples).

Every field of every result dataclass is kept, in field order, as a tuple: floats keep all
their bits (nan and inf too), ints stay ints, tuples stay tuples.  Decoding calls each
dataclass on its fields and converts only the fields that hold dataclasses.  So
``decode(encode(report)) == report`` field for field, and every reporter renders the
decoded report to the same bytes as the original.  The layout follows the dataclasses'
fields (read from their type hints), so a field added to a result class is carried without
a change here; the cache's key holds a digest of furncheck's source, so entries written by
another version are never decoded.
"""

from __future__ import annotations

import dataclasses
import functools
import types
import typing
from collections.abc import Callable
from typing import Any

from furncheck.result import DesignReport

Decoder = Callable[[Any], Any]


class CodecError(ValueError):
    """Data that is not an encoded report (a damaged cache entry)."""


_PLAIN = (str, int, float, bool, type(None))


def encode(value: Any) -> Any:
    """``value`` (a result dataclass, tuple, or scalar) as nested tuples and scalars; a
    numpy scalar becomes the Python scalar of the same value (``.item()``)."""
    if type(value) in _PLAIN:
        return value
    if dataclasses.is_dataclass(value):
        return tuple(encode(getattr(value, item.name)) for item in dataclasses.fields(value))
    if isinstance(value, (tuple, list)):
        return tuple(encode(item) for item in value)
    if hasattr(value, "item"):
        return value.item()
    raise TypeError(f"cannot encode a {type(value).__name__}")


def decode_report(data: Any) -> DesignReport:
    """The ``DesignReport`` that ``encode`` turned into ``data``; CodecError when ``data``
    is not one."""
    try:
        return _decoder(DesignReport)(data)
    except (TypeError, ValueError, IndexError, KeyError) as error:
        raise CodecError(f"not an encoded report: {error}") from None


@functools.cache
def _decoder(hint: Any) -> Decoder | None:
    """A function that turns encoded data back into a value of the type ``hint``; None
    where the data is the value already (scalars, tuples of scalars).  Scalars are not
    checked one by one (a cache entry is checked whole against its CRC,
    ``furncheck.cache``); a wrong shape fails here (CodecError, TypeError)."""
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        return _dataclass_decoder(hint)
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        options = [option for option in typing.get_args(hint) if option is not type(None)]
        if len(options) != 1:
            raise TypeError(f"cannot decode {hint}")
        inner = _decoder(options[0])
        if inner is None:
            return None
        return lambda data: None if data is None else inner(data)
    if origin is tuple:
        arguments = typing.get_args(hint)
        if len(arguments) == 2 and arguments[1] is Ellipsis:
            item = _decoder(arguments[0])
            if item is None:
                return None
            return lambda data: tuple(map(item, data))
        if all(_decoder(argument) is None for argument in arguments):
            return None
        raise TypeError(f"cannot decode {hint}")
    if hint in (str, int, float, bool):
        return None
    raise TypeError(f"cannot decode {hint}")


def _dataclass_decoder(kind: type) -> Decoder:
    """``kind(*data)``, the fields that hold dataclasses decoded first."""
    hints = typing.get_type_hints(kind)
    names = [item.name for item in dataclasses.fields(kind)]
    conversions = [(index, part) for index, name in enumerate(names)
                   if (part := _decoder(hints[name])) is not None]
    count = len(names)

    def decode(data: Any) -> Any:
        if type(data) is not tuple or len(data) != count:
            raise CodecError(f"{kind.__name__}: expected {count} fields")
        if not conversions:
            return kind(*data)
        values = list(data)
        for index, part in conversions:
            values[index] = part(values[index])
        return kind(*values)
    return decode
