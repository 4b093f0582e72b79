#include "cad_reader.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <mutex>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>

namespace wefm_cad {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// STEP and IGES readers share XSControl's interface: read, transfer every root, take one shape.
template <class Reader>
bool read_exchange(const std::string& path, const char* what, TopoDS_Shape& shape, std::string& error) {
  Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
    error = std::string("cannot read ") + what + " file " + path;
    return false;
  }
  if (reader.TransferRoots() <= 0) {
    error = path + ": no " + what + " entity could be transferred to a shape";
    return false;
  }
  shape = reader.OneShape();
  return true;
}

// OCCT's translators print statistics to stdout through the default messenger, which would mix
// with the tool's tables. Only failures are kept, on stderr.
void quiet_occt_messages() {
  static std::once_flag once;
  std::call_once(once, [] {
    const Handle(Message_Messenger)& messenger = Message::DefaultMessenger();
    messenger->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    messenger->AddPrinter(new Message_PrinterOStream("cerr", Standard_False, Message_Fail));
  });
}

}  // namespace

bool read_cad_shape(const std::string& path, TopoDS_Shape& shape, std::string& format, std::string& error) {
  if (!std::filesystem::is_regular_file(path)) {
    error = "cannot open " + path + ": no such file";
    return false;
  }
  const std::string ext = lower_extension(path);
  quiet_occt_messages();
  try {
    bool ok = false;
    if (ext == ".step" || ext == ".stp") {
      format = "step";
      ok = read_exchange<STEPControl_Reader>(path, "STEP", shape, error);
    } else if (ext == ".iges" || ext == ".igs") {
      format = "iges";
      ok = read_exchange<IGESControl_Reader>(path, "IGES", shape, error);
    } else if (ext == ".brep" || ext == ".rle") {
      format = "brep";
      BRep_Builder builder;
      ok = BRepTools::Read(shape, path.c_str(), builder);
      if (!ok) error = "cannot read " + path + " as an Open CASCADE BREP file";
    } else {
      error = path + ": unknown CAD format '" + ext + "' (expected .step/.stp, .iges/.igs, .brep/.rle)";
      return false;
    }
    if (ok && shape.IsNull()) {
      error = path + ": the file holds no shape";
      ok = false;
    }
    return ok;
  } catch (const Standard_Failure& f) {
    error = path + ": Open CASCADE: " + f.GetMessageString();
  } catch (const std::exception& e) {
    error = path + ": " + e.what();
  }
  return false;
}

}  // namespace wefm_cad
