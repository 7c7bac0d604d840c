#include "service/model/model_check.h"

#include <map>

#include "service/model/description_check.h"

namespace contactsim::model {

std::string ModelWhere(const ModelDescription& d) { return "model \"" + d.name + "\" (" + d.source + ")"; }

Status CheckModel(ModelDescription* d, ModelTree* tree) {
  SourceMap where;
  where.file = d->source.empty() ? "<inline>" : d->source;
  Status st = CheckCounts(d->links.size(), d->joints.size(), ReadLimits(), where);
  if (st.ok()) st = CheckTree(where, d);
  if (st.ok()) st = CheckValues(where, d);
  if (!st.ok()) return st.Prefixed("model \"" + d->name + "\": ");
  std::map<std::string, int> link_index;
  for (size_t i = 0; i < d->links.size(); ++i) link_index[d->links[i].name] = static_cast<int>(i);
  ModelTree t;
  t.root = link_index.at(d->root_link);
  t.parent_joint.assign(d->links.size(), -1);
  t.parent_link.assign(d->links.size(), -1);
  std::vector<std::vector<int>> children(d->links.size());
  for (size_t i = 0; i < d->joints.size(); ++i) {
    const int c = link_index.at(d->joints[i].child), p = link_index.at(d->joints[i].parent);
    t.parent_joint[c] = static_cast<int>(i);
    t.parent_link[c] = p;
    children[p].push_back(c);
  }
  // breadth first from the root (CheckTree has ruled out loops)
  t.order.push_back(t.root);
  for (size_t k = 0; k < t.order.size(); ++k) {
    for (int c : children[t.order[k]]) t.order.push_back(c);
  }
  *tree = std::move(t);
  return Status::Ok();
}

}  // namespace contactsim::model
