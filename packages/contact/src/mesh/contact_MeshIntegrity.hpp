#pragma once
// Checks of a mesh file that Gmsh's reader does not make. Gmsh keeps one of two nodes (or
// elements) that share a tag without a word, so a typing mistake in a hand-edited .msh would
// silently move a node; and two distinct nodes at one point inside a body cut it (a crack the
// user did not model). Both are errors that name the file and the tags.

#include <string>
#include <vector>

namespace contact {

// Scans the $Nodes and $Elements sections of an ASCII .msh file (format 2.x or 4.x) and throws
// std::runtime_error naming `path`, the tag and both line numbers if a node or element tag is
// defined twice. Binary files are not scanned (Gmsh's own reader checks their block sizes).
void checkUniqueMshTags(const std::string& path);

// Throws if two distinct nodes used by the elements of one body lie at the same point (within
// 1e-12 of the model's extent). `coords` holds `dim` values per node, `nodes` the nodes the body
// uses (compact ids), `tags` their Gmsh tags for the message.
void checkNoCoincidentNodes(const std::string& path, const std::string& body, int dim,
                            const std::vector<double>& coords, const std::vector<int>& nodes,
                            const std::vector<std::size_t>& tags);

}  // namespace contact
