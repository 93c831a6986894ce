#pragma once
// OpenCASCADE shapes written as STEP and IGES files by OpenCASCADE's own writers, for the tests
// that read them back (the file as another CAD system would write it).

#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Shape.hxx>

#include <catch2/catch.hpp>

#include <string>

namespace plyfit::test {

/// Writes `shape` as an AP214 STEP file in `unit` ("MM", "INCH", ...).
inline void write_step(const TopoDS_Shape& shape, const std::string& path,
                       const char* unit = "MM") {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", unit);
  STEPControl_Writer w;
  REQUIRE(w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone);
  REQUIRE(w.Write(path.c_str()) == IFSelect_RetDone);
  Interface_Static::SetCVal("write.step.unit", "MM");
}

/// Writes `shape` as an IGES file in `unit`, in BRep mode (186/514/510 entities with analytic
/// surfaces).
inline void write_iges(const TopoDS_Shape& shape, const std::string& path,
                       const char* unit = "MM") {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  IGESControl_Controller::Init();
  IGESControl_Writer w(unit, 1);
  REQUIRE(w.AddShape(shape));
  w.ComputeModel();
  REQUIRE(w.Write(path.c_str()));
}

}  // namespace plyfit::test
