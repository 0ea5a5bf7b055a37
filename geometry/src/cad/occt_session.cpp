// hotmesh geometry (internal): one OpenCASCADE data-exchange user at a time, with its global
// parameters and messenger restored afterwards.
#include "cad/occt_session.hpp"

#include <IGESControl_Controller.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <UnitsMethods.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <OSD.hxx>

#include <pthread.h>

#include <algorithm>
#include <iterator>
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

namespace {

// Every signal OSD::SetSignal handles, and those whose handling hotmesh keeps from it.
constexpr int kOcctSignals[] = {SIGFPE, SIGHUP, SIGINT, SIGQUIT, SIGILL, SIGBUS, SIGSYS, SIGSEGV};
constexpr int kFaults[] = {SIGILL, SIGBUS, SIGSYS, SIGSEGV};

bool is_fault(int signal) { return std::find(std::begin(kFaults), std::end(kFaults), signal) != std::end(kFaults); }

}  // namespace

FaultsAsFailures::FaultsAsFailures() {
  for (const int signal : kOcctSignals) {
    struct sigaction old {};
    ::sigaction(signal, nullptr, &old);
    saved_.emplace_back(signal, old);
  }
  OSD::SetSignal(OSD_SignalMode_Set, /*theFloatingSignal=*/false);
  handler_stack_.resize(std::max<std::size_t>(static_cast<std::size_t>(SIGSTKSZ), 256 * 1024));
  stack_t stack{};
  stack.ss_sp = handler_stack_.data();
  stack.ss_size = handler_stack_.size();
  ::sigaltstack(&stack, &saved_stack_);
  for (const auto& [signal, old] : saved_) {
    if (!is_fault(signal)) {
      ::sigaction(signal, &old, nullptr);
      continue;
    }
    struct sigaction occt {};
    ::sigaction(signal, nullptr, &occt);
    occt.sa_flags |= SA_ONSTACK;
    ::sigaction(signal, &occt, nullptr);
  }
}

FaultsAsFailures::~FaultsAsFailures() {
  sigset_t faults;
  sigemptyset(&faults);
  for (const auto& [signal, old] : saved_) {
    ::sigaction(signal, &old, nullptr);
    if (is_fault(signal)) sigaddset(&faults, signal);
  }
  // A fault's handler left by a jump: the signal may still be blocked in this thread.
  ::pthread_sigmask(SIG_UNBLOCK, &faults, nullptr);
  ::sigaltstack(&saved_stack_, nullptr);
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
