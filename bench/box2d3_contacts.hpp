// Box2D v3's own deepest overlap: the largest −separation over the contact manifolds of
// `bodies` (each with a b2BodyId `id`), for the shapes' and joints' steppers
// (boxes_box2d3.cpp, joints_box2d3.cpp). Included after box2d.h inside a release's namespace:
// each release compiles its own copy; the including file has included <algorithm> and
// <vector> before. Internal to bench/.
#pragma once

/// b2ContactData as an element of a vector (an array of one is one of the other).
struct ContactDataRef {
  b2ContactData data;
};
static_assert(sizeof(ContactDataRef) == sizeof(b2ContactData));

template <class Bodies>
[[nodiscard]] double deepest_manifold_overlap(const Bodies& bodies) {
  double deepest = 0.0;
  std::vector<ContactDataRef> contacts;
  for (const auto& b : bodies) {
    const int capacity = b2Body_GetContactCapacity(b.id);
    if (capacity <= 0) continue;
    contacts.resize(std::size_t(capacity));
    const int n = b2Body_GetContactData(b.id, &contacts.data()->data, int(contacts.size()));
    for (int c = 0; c < n; ++c) {
      const b2Manifold& m = contacts[std::size_t(c)].data.manifold;
      for (int k = 0; k < m.pointCount; ++k) {
        deepest = std::max(deepest, -double(m.points[k].separation));
      }
    }
  }
  return deepest;
}
