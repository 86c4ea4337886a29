// Internal: the XML dictionaries of one ShadingContext, for dict_find / dict_next / dict_value
// (runtime/shadeops/ops_dict.cpp). Not part of the renderer API.
//
// A dictionary is XML text, or the name of a file ending in ".xml"; it is parsed once and kept
// for the context's life. Queries are XPath (pugixml). Every match of a query gets a node id
// (1, 2, ...; 0 means "none"), numbered in the order queries are first made, so ids are stable
// for the context's life and a query asked again returns the same first id, as in OSL.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace lobe::detail {

class Dictionaries {
public:
  Dictionaries();
  ~Dictionaries();
  Dictionaries(const Dictionaries&) = delete;
  Dictionaries& operator=(const Dictionaries&) = delete;

  // The first node matching `query` in the document `dict`: its id, 0 if nothing matches (or
  // the query is invalid), -1 if the document does not parse. `error` receives a message the
  // first time a document or a query fails (OSL's wording), else stays empty.
  int find(std::string_view dict, std::string_view query, std::string& error);
  // The first match of `query` relative to node `node`; 0 for an invalid node.
  int find(int node, std::string_view query, std::string& error);
  // The node after `node` among the matches of the query that found it; 0 at the end.
  int next(int node) const;
  // The text of attribute `attribute` of node `node`, or of the node's own value when
  // `attribute` is empty; nullopt for an invalid node or a missing attribute. The text lives as
  // long as this object.
  std::optional<std::string_view> value(int node, std::string_view attribute) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace lobe::detail
