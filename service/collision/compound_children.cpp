#include "service/collision/compound_children.h"

namespace contactsim {

RigidBody ChildBody(const RigidBody& parent, const ShapeChild& child) {
  RigidBody b;
  b.id = parent.id;
  b.motion = parent.motion;
  b.material = parent.material;
  b.shape = child.shape;
  b.x = parent.x + parent.q * child.position;
  b.q = parent.q * child.orientation;
  return b;
}

int PieceCount(const RigidBody& body) {
  if (body.shape.type != ShapeType::kCompound || body.shape.compound == nullptr) return 1;
  return static_cast<int>(body.shape.compound->children.size());
}

RigidBody PieceBody(const RigidBody& body, int k) {
  if (body.shape.type != ShapeType::kCompound || body.shape.compound == nullptr) {
    RigidBody piece;
    piece.id = body.id;
    piece.motion = body.motion;
    piece.material = body.material;
    piece.shape = body.shape;
    piece.x = body.x;
    piece.q = body.q;
    return piece;
  }
  return ChildBody(body, body.shape.compound->children[k]);
}

}  // namespace contactsim
