"""`@record`: classes with fields, made as `@dataclass` makes them, for the
modules `epuckc check` imports.

Importing `dataclasses` imports `inspect` (and `dis`, `ast`, `tokenize`):
about 10 ms of every `check`, plus some 0.3 ms to decorate each class. A
record is what the dataclass would be for the features epuckc uses: an
`__init__` with the fields in order (defaults and `field(default_factory=)`
allowed), equality by type and fields, a `Name(field=...)` repr, and with
`frozen=True` hashing by fields and assignment raising FrozenInstanceError.

Records also answer to the `dataclasses` module (`dataclasses.replace`,
`fields`, `asdict`, `is_dataclass`): their `__dataclass_fields__` is made
the first time something asks for it, so only code that uses dataclasses
imports it. `tests/syntax/test_records.py` keeps both behaviours, and
`check` free of `dataclasses`.
"""
from __future__ import annotations

__all__ = ["FrozenInstanceError", "field", "record"]

_MISSING = object()


class FrozenInstanceError(AttributeError):
    """Assigning to a field of a frozen record."""


class _Field:
    __slots__ = ("default", "default_factory")

    def __init__(self, default, default_factory):
        self.default = default
        self.default_factory = default_factory


def field(*, default=_MISSING, default_factory=_MISSING):
    """A field's default, as dataclasses.field: a value or a factory."""
    if default is not _MISSING and default_factory is not _MISSING:
        raise ValueError("cannot give both default and default_factory")
    return _Field(default, default_factory)


class _LazyDataclassFields:
    """`__dataclass_fields__`, made on first use (importing dataclasses)."""

    def __get__(self, obj, cls):
        import dataclasses
        fields = {}
        for name, default, factory in cls.__record_fields__:
            f = dataclasses.field(default=dataclasses.MISSING if default is _MISSING else default,
                                  default_factory=dataclasses.MISSING if factory is _MISSING
                                  else factory)
            f.name = name
            f.type = cls.__annotations__.get(name)
            f._field_type = dataclasses._FIELD
            fields[name] = f
        setattr(cls, "__dataclass_fields__", fields)
        return fields


def _frozen_setattr(self, name, value):
    raise FrozenInstanceError(f"cannot assign to field {name!r}")


def _frozen_delattr(self, name):
    raise FrozenInstanceError(f"cannot delete field {name!r}")


def _repr(self):
    inside = ", ".join(f"{name}={getattr(self, name)!r}" for name in self.__match_args__)
    return f"{type(self).__qualname__}({inside})"


def _eq(self, other):
    if other.__class__ is not self.__class__:
        return NotImplemented
    names = self.__match_args__
    return tuple(getattr(self, n) for n in names) == tuple(getattr(other, n) for n in names)


def _hash(self):
    return hash(tuple(getattr(self, n) for n in self.__match_args__))


def record(cls=None, *, frozen: bool = False):
    """Decorate a class whose annotations are its fields (see the module)."""
    def wrap(cls):
        names = list(cls.__dict__.get("__annotations__", {}))
        fields, params, body = [], [], []
        namespace = {"_set": object.__setattr__, "_MISSING": _MISSING}
        seen_default = False
        for name in names:
            value = cls.__dict__.get(name, _MISSING)
            default, factory = _MISSING, _MISSING
            if isinstance(value, _Field):
                default, factory = value.default, value.default_factory
            elif value is not _MISSING:
                default = value
            if factory is not _MISSING:
                namespace[f"_factory_{name}"] = factory
                params.append(f"{name}=_MISSING")
                value_text = f"_factory_{name}() if {name} is _MISSING else {name}"
                seen_default = True
                if name in cls.__dict__:
                    delattr(cls, name)
            elif default is not _MISSING:
                namespace[f"_default_{name}"] = default
                params.append(f"{name}=_default_{name}")
                value_text = name
                seen_default = True
                setattr(cls, name, default)     # as dataclasses leaves it
            else:
                if seen_default:
                    raise TypeError(f"non-default field {name!r} follows a default one")
                params.append(name)
                value_text = name
            body.append(f"_set(self, {name!r}, {value_text})" if frozen
                        else f"self.{name} = {value_text}")
            fields.append((name, default, factory))
        source = (f"def __init__(self, {', '.join(params)}):\n    "
                  + ("\n    ".join(body) or "pass") + "\n")
        exec(source, namespace)
        init = namespace["__init__"]
        init.__qualname__ = f"{cls.__qualname__}.__init__"
        cls.__init__ = init
        cls.__record_fields__ = tuple(fields)
        cls.__match_args__ = tuple(names)
        cls.__dataclass_fields__ = _LazyDataclassFields()
        if "__repr__" not in cls.__dict__:
            cls.__repr__ = _repr
        if "__eq__" not in cls.__dict__:
            cls.__eq__ = _eq
        if frozen:
            cls.__setattr__ = _frozen_setattr
            cls.__delattr__ = _frozen_delattr
            cls.__hash__ = _hash
        elif "__hash__" not in cls.__dict__:
            cls.__hash__ = None       # mutable and compared by value: unhashable
        return cls

    return wrap if cls is None else wrap(cls)
