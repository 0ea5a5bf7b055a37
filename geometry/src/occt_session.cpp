// hotmesh geometry (internal): one OpenCASCADE data-exchange user at a time, with its global
// parameters and messenger restored afterwards.
#include "occt_session.hpp"

#include <IGESControl_Controller.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <UnitsMethods.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>

#include <stdexcept>

namespace hotmesh::geometry::detail {

namespace {

std::mutex& exchange_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

OcctSession::OcctSession() : lock_(exchange_mutex()) {
  const Handle(Message_Messenger)& messenger = Message::DefaultMessenger();
  printers_ = messenger->Printers();
  messenger->ChangePrinters().Clear();
  STEPControl_Controller::Init();
  IGESControl_Controller::Init();
}

OcctSession::~OcctSession() {
  for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
    Interface_Static::SetCVal(it->first.c_str(), it->second.c_str());
  }
  if (saved_unit_in_mm_ > 0.0) UnitsMethods::SetCasCadeLengthUnit(saved_unit_in_mm_, UnitsMethods_LengthUnit_Millimeter);
  Message::DefaultMessenger()->ChangePrinters() = printers_;
}

void OcctSession::use_unit(LengthUnit unit) {
  set("xstep.cascade.unit", occt_unit_name(unit));
  if (!(saved_unit_in_mm_ > 0.0)) saved_unit_in_mm_ = UnitsMethods::GetCasCadeLengthUnit();
  UnitsMethods::SetCasCadeLengthUnit(Interface_Static::IVal("xstep.cascade.unit"));
}

void OcctSession::set(const char* name, const char* value) {
  if (!Interface_Static::IsPresent(name)) throw std::logic_error(std::string("no OpenCASCADE parameter ") + name);
  saved_.emplace_back(name, Interface_Static::CVal(name));
  if (!Interface_Static::SetCVal(name, value)) {
    throw std::logic_error(std::string("OpenCASCADE refused ") + name + " = " + value);
  }
}

const char* occt_unit_name(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::metre: return "M";
    case LengthUnit::millimetre: return "MM";
    case LengthUnit::centimetre: return "CM";
    case LengthUnit::micrometre: return "UM";
    case LengthUnit::inch: return "INCH";
    case LengthUnit::foot: return "FT";
  }
  return "M";
}

}  // namespace hotmesh::geometry::detail
