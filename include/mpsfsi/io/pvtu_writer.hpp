// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/io/detail/output_file.hpp"
#include "mpsfsi/io/vtu_writer.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Writes the index of a parallel VTK UnstructuredGrid (.pvtu): the file names of its pieces
// (.vtu files, relative to the index, as ParaView resolves them) and the point arrays they all
// hold, as `layout` (the writer of any one piece) declares them. The pieces are written
// separately, one per process (mpi/distributed_output.hpp). A .pvd may list .pvtu files.
template <int Dim, class Scalar>
void write_pvtu(const std::string& path, const VtuWriter<Dim, Scalar>& layout, const std::vector<std::string>& pieces) {
  if (pieces.empty()) detail::throw_invalid("write_pvtu", "no pieces");
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"";
  xml += detail::host_is_little_endian() ? "LittleEndian" : "BigEndian";
  xml += "\" header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n";
  layout.for_each_declaration([&xml](const char* type, const std::string& name, int components) {
    xml += "      <PDataArray type=\"" + std::string(type) + "\" Name=\"" + detail::xml_escape(name) +
           "\" NumberOfComponents=\"" + std::to_string(components) + "\"/>\n";
  });
  xml += "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"" + std::string(layout.points_type()) +
         "\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const std::string& piece : pieces) xml += "    <Piece Source=\"" + detail::xml_escape(piece) + "\"/>\n";
  xml += "  </PUnstructuredGrid>\n</VTKFile>\n";
  detail::AtomicFile out("write_pvtu", path);
  out.write(xml);
  out.commit();
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
