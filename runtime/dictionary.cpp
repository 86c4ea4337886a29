// Dictionaries (lobe/detail/dictionary.h): XML documents parsed with pugixml, XPath queries, and
// the node ids dict_find hands out. The numbering follows OSL's: id 0 is "none", every new
// (document or node, query) pair appends its matches, chained by `next` in the order pugixml
// returns them; a failed document or query is remembered so that it is reported once.
#include "lobe/detail/dictionary.h"

#include <pugixml.hpp>

#include <map>
#include <tuple>
#include <vector>

namespace lobe::detail {

struct Dictionaries::Impl {
  struct Node {
    int document = -1;
    pugi::xml_node node; // null for a match that is an attribute (its value reads as "")
    int next = 0;
  };
  std::vector<std::unique_ptr<pugi::xml_document>> documents;
  std::map<std::string, int, std::less<>> by_text; // document index, -1: does not parse
  std::vector<Node> nodes{1};                      // nodes[0]: "none"
  // (document, node the query is relative to (0: the document), query) -> first match or 0.
  std::map<std::tuple<int, int, std::string>, int, std::less<>> queries;

  int document(std::string_view dict, std::string& error);
  int select(int doc, int from, const pugi::xml_node& root, std::string_view query,
             std::string& error);
};

// The index of document `dict` (parsed on first use), or -1.
int Dictionaries::Impl::document(std::string_view dict, std::string& error) {
  if (auto it = by_text.find(dict); it != by_text.end()) return it->second;
  auto doc = std::make_unique<pugi::xml_document>();
  bool file = dict.size() >= 4 && dict.substr(dict.size() - 4) == ".xml";
  pugi::xml_parse_result r =
      file ? doc->load_file(std::string(dict).c_str()) : doc->load_buffer(dict.data(), dict.size());
  int index = -1;
  if (r) {
    documents.push_back(std::move(doc));
    index = int(documents.size()) - 1;
  } else {
    error = "XML parsed with errors: " + std::string(r.description()) + ", at offset " +
            std::to_string(r.offset);
  }
  by_text.emplace(std::string(dict), index);
  return index;
}

// The first match of `query` under `root` (node id `from`, 0 for the document itself).
int Dictionaries::Impl::select(int doc, int from, const pugi::xml_node& root,
                               std::string_view query, std::string& error) {
  auto key = std::make_tuple(doc, from, std::string(query));
  if (auto it = queries.find(key); it != queries.end()) return it->second;
  int& first = queries[key];
  pugi::xpath_node_set matches;
  try { // pugixml reports a malformed query by throwing
    matches = pugi::xpath_query(std::get<2>(key).c_str()).evaluate_node_set(root);
  } catch (const pugi::xpath_exception& e) {
    error = "Invalid dict_find query '" + std::get<2>(key) + "': " + e.result().description();
    return first = 0;
  }
  int last = 0;
  for (const pugi::xpath_node& m : matches) {
    nodes.push_back(Node{doc, m.node(), 0});
    int id = int(nodes.size()) - 1;
    if (last)
      nodes[size_t(last)].next = id;
    else
      first = id;
    last = id;
  }
  return first;
}

Dictionaries::Dictionaries() : impl_(std::make_unique<Impl>()) {}
Dictionaries::~Dictionaries() = default;

int Dictionaries::find(std::string_view dict, std::string_view query, std::string& error) {
  int doc = impl_->document(dict, error);
  if (doc < 0) return -1;
  return impl_->select(doc, 0, *impl_->documents[size_t(doc)], query, error);
}

int Dictionaries::find(int node, std::string_view query, std::string& error) {
  if (node <= 0 || node >= int(impl_->nodes.size())) return 0;
  const Impl::Node& n = impl_->nodes[size_t(node)];
  return impl_->select(n.document, node, n.node, query, error);
}

int Dictionaries::next(int node) const {
  if (node <= 0 || node >= int(impl_->nodes.size())) return 0;
  return impl_->nodes[size_t(node)].next;
}

std::optional<std::string_view> Dictionaries::value(int node, std::string_view attribute) const {
  if (node <= 0 || node >= int(impl_->nodes.size())) return std::nullopt;
  const pugi::xml_node& n = impl_->nodes[size_t(node)].node;
  if (attribute.empty()) return std::string_view(n.value());
  for (const pugi::xml_attribute& a : n.attributes())
    if (attribute == a.name()) return std::string_view(a.value());
  return std::nullopt;
}

} // namespace lobe::detail
