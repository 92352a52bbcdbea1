"""Columnar export: the messages of a capture as columns per command, a ``dict`` of lists or a
pandas ``DataFrame``, so that a field over time is one column.

A column is named by its place in the message: ``offset`` (where the frame starts in the
capture), ``header.NAME`` for a header value, and the payload's field name, with nested
structs joined by dots (``utc_time.year``). Arrays and repeated groups stay one column of
lists.
"""

from __future__ import annotations

from typing import Any, Dict, Iterable, List, Optional

from ._native import Message

Columns = Dict[str, List[Any]]


def _flatten(prefix: str, value: Any, row: Dict[str, Any]) -> None:
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(f"{prefix}.{k}" if prefix else k, v, row)
    else:
        row[prefix] = value


def _row(msg: Message) -> Dict[str, Any]:
    d = msg.to_dict()
    row: Dict[str, Any] = {"offset": d["offset"]}
    _flatten("header", d["header"], row)
    payload = d["payload"]
    if isinstance(payload, dict):
        _flatten("", payload, row)
    else:
        row["payload"] = payload
    return row


def to_columns(messages: Iterable[Any], command: Optional[str] = None) -> Dict[str, Columns]:
    """The messages as columns, per command name: ``{"ATTITUDE": {"offset": [...],
    "header.seq": [...], "roll": [...], ...}, ...}``. Events among ``messages`` are skipped;
    so are acknowledgements and frames without command (their name is ``None``). With
    ``command``, only that command's columns are gathered, under its name.

    A column missing from some rows (an optional field) holds ``None`` there."""
    tables: Dict[str, Columns] = {}
    counts: Dict[str, int] = {}
    for msg in messages:
        if not isinstance(msg, Message) or msg.name is None:
            continue
        if command is not None and msg.name != command:
            continue
        table = tables.setdefault(msg.name, {})
        n = counts.get(msg.name, 0)
        row = _row(msg)
        for key, value in row.items():
            column = table.get(key)
            if column is None:
                column = table[key] = [None] * n
            column.append(value)
        for key, column in table.items():
            if key not in row:
                column.append(None)
        counts[msg.name] = n + 1
    return tables


def to_dataframe(messages: Iterable[Any], command: str) -> Any:
    """The messages of ``command`` as a pandas ``DataFrame``, one row per message, one column
    per field (see :func:`to_columns`). Needs pandas (``pip install pandas``)."""
    try:
        import pandas  # type: ignore[import-not-found]
    except ImportError as e:
        raise ImportError("to_dataframe needs pandas: pip install pandas") from e
    columns = to_columns(messages, command).get(command, {})
    return pandas.DataFrame(columns)
