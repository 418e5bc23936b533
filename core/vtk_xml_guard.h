// What VTK 9.1's XML readers must not be given: file features on which they crash instead of
// reporting an error. Checked on the file's text before a reader sees it.
//
//  - A DataArray (or Array) of a type VTK cannot make ("Int33", none): vtkXMLReader creates no
//    array and dereferences it anyway (field data in ReadXMLInformation, piece data later).
//    Refused: InputError naming the file and the type.
//  - A piece with cell data but no <PointData> element: reporting a cell array shorter than the
//    cell count, vtkXMLDataReader::ReadPieceData names the point-data element in its message and
//    dereferences a null pointer. Such a file is given an empty <PointData></PointData> before
//    each <CellData> (VTK's own writers always write one, so their files are read as they are).
//
// Only the XML part is scanned (up to <AppendedData>); appended binary data is not looked at.
#pragma once

#include <string>

namespace tissuemesh {

/// Checks the VTK XML file `path` (above). Returns "" when the file can be read as it is, else the
/// whole text to read instead (vtkXMLReader::SetInputString). Throws InputError naming `path`.
std::string vtk_xml_text_to_read(const std::string& path);

}  // namespace tissuemesh
