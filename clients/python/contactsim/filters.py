"""Collision filter commands of the Client, on <prefix>_BODY_CMD (docs/protocol.md).

Every body has a filter as Box2D's b2Filter: ``collision_category`` (the
bits the body is, default 1), ``collision_mask`` (the bits it touches,
default all 32) and ``collision_group`` (default 0). Two bodies touch when
(category_a & mask_b) and (category_b & mask_a) are both nonzero, except
that two bodies of one nonzero group always touch when the group is
positive and never when it is negative (docs/physics.md, "Collision
filtering"). The add_ methods take the same three keywords.
"""
import numbers

from . import body_cmd_t

_U32 = (1 << 32) - 1


def _integer(value, field, low, high):
    # bool is an int in Python, but True as a mask is a mistake, not bit 0
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError("%s must be an integer, got %r" % (field, value))
    if not low <= int(value) <= high:
        raise ValueError("%s must be in [%d, %d], got %d" % (field, low, high, int(value)))
    return int(value)


def _signed32(bits):
    """The int32 the wire carries for a 32-bit set (LCM has no unsigned types)."""
    return bits - (1 << 32) if bits >= (1 << 31) else bits


def fill_filter(m, category=None, mask=None, group=None):
    """Sets a body_cmd_t's filter fields; None keeps that one's default.
    Returns whether any was given (ADD's has_filter)."""
    given = not (category is None and mask is None and group is None)
    m.collision_category = _signed32(_integer(1 if category is None else category, "collision_category", 0, _U32))
    m.collision_mask = _signed32(_integer(_U32 if mask is None else mask, "collision_mask", 0, _U32))
    m.collision_group = _integer(0 if group is None else group, "collision_group", -(1 << 31), (1 << 31) - 1)
    m.has_filter = given
    return given


class FilterCommands:
    """Mixin of Client: needs its ``_send(channel, msg)`` and ``_body(op, id)``."""

    def set_filter(self, body_id, collision_category=1, collision_mask=_U32, collision_group=0):
        """Replaces a body's collision filter (all three fields; the defaults
        touch every body). Wakes the body and what touches it; a pair the new
        filter excludes loses its contacts from the next step on."""
        m = self._body(body_cmd_t.SET_FILTER, body_id)
        fill_filter(m, collision_category, collision_mask, collision_group)
        return self._send("BODY_CMD", m)
