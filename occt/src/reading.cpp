// The reading step shared by the STEP and IGES readers (mold_file.hpp): the checks of a file
// before it is read, the guard and deadline around OpenCASCADE's reader, the summary of its
// messages and the faces' names and entities.
#include "geometry_checks.hpp"
#include "mold_file.hpp"

#include <Interface_Check.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <OSD.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TransferBRep.hxx>
#include <Transfer_Binder.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

namespace plyfit::importers::occt {

namespace {

// A recursion that overflows the stack, as a reader's recursion that does not end would.
[[gnu::noinline]] int recurse(int depth) {
  volatile char frame[1024];
  frame[0] = static_cast<char>(depth);
  if (depth > (1 << 30)) return 0;  // never: the stack ends first
  return recurse(depth + 1) + frame[0];
}

std::string read_head(std::ifstream& in, size_t n) {
  std::string s(n, '\0');
  in.read(s.data(), static_cast<std::streamsize>(n));
  s.resize(static_cast<size_t>(in.gcount()));
  return s;
}

// A STEP file ends with END-ISO-10303-21; an IGES file with its Terminate section (a line
// with 'T' in column 73). Their absence means the file was cut short.
bool looks_complete(Sniffed format, const std::string& tail) {
  if (format == Sniffed::kStep) return tail.find("END-ISO-10303-21") != std::string::npos;
  std::istringstream is(tail);
  std::string line, last;
  while (std::getline(is, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) last = line;
  }
  return last.size() >= 73 && last[72] == 'T';
}

}  // namespace

Result<Sniffed> check_file_head(const std::string& path, const std::string& format_key) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (ec || !fs::exists(st)) return Error{ErrorCode::kFileMissing, path};
  if (!fs::is_regular_file(st)) return Error{ErrorCode::kFileNotRegular, path};
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{ErrorCode::kFileNotReadable, path};
  const std::string head = read_head(in, 4096);
  if (head.find_first_not_of(" \t\r\n") == std::string::npos)
    return Error{ErrorCode::kFileEmpty, path};
  const Sniffed want = format_key == "step" ? Sniffed::kStep : Sniffed::kIges;
  const Sniffed got = sniff(head);
  const std::string upper = format_key == "step" ? "STEP" : "IGES";
  if (got != want) {
    const std::string looks = got == Sniffed::kStep ? "STEP" : got == Sniffed::kIges ? "IGES" : "";
    return Error{ErrorCode::kFileWrongFormat, path, {upper, looks}};
  }
  const auto file_size = fs::file_size(path, ec);
  if (!ec && file_size > 4096) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(file_size - 4096));
  } else {
    in.clear();
    in.seekg(0);
  }
  if (!looks_complete(want, read_head(in, 4096)))
    return Error{ErrorCode::kFileTruncated, path, {upper}};
  return want;
}

void debug_reader_fault() {
  const char* fault = std::getenv("PLYFIT_DEBUG_READER_FAULT");
  if (!fault) return;
  if (std::string(fault) == "segv") std::raise(SIGSEGV);
  if (std::string(fault) == "stack") recurse(0);
}

Deadline::Deadline(double seconds)
    : end_(std::chrono::steady_clock::now() +
           std::chrono::duration_cast<std::chrono::steady_clock::duration>(
               std::chrono::duration<double>(seconds))),
      seconds_(seconds) {}

bool Deadline::expired() const {
  return std::chrono::steady_clock::now() > end_;
}

Sniffed sniff(const std::string& head) {
  size_t i = head.find_first_not_of(" \t\r\n");
  if (i == std::string::npos) return Sniffed::kUnknown;
  if (head.compare(i, 12, "ISO-10303-21") == 0) return Sniffed::kStep;
  // IGES: fixed 80-column records with the section letter in column 73 (S or, without a
  // start section, G).
  const size_t eol = head.find('\n');
  std::string first = head.substr(0, eol);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  if (first.size() >= 73 && (first[72] == 'S' || first[72] == 'G')) return Sniffed::kIges;
  return Sniffed::kUnknown;
}

void prepare_occt() {
  static std::once_flag once;
  std::call_once(once, [] {
    // OpenCASCADE's messages are summarised into Mold::warnings, never printed raw.
    Message::DefaultMessenger()->ChangePrinters().Clear();
  });
}

namespace {
// The signals OSD::SetSignal installs handlers for on Linux.
constexpr int kOsdSignals[] = {SIGHUP, SIGINT,  SIGQUIT, SIGILL, SIGTRAP,
                               SIGBUS, SIGSEGV, SIGSYS,  SIGFPE};
// The stack the fault handlers run on: a reader that overflows its own stack (a recursion that
// does not end) leaves none for them. OpenCASCADE's handler formats a message and allocates the
// exception it jumps with.
constexpr size_t kSignalStackBytes = 256 * 1024;
}  // namespace

struct SignalScope::Saved {
  struct sigaction actions[std::size(kOsdSignals)];
  stack_t stack{};
  std::unique_ptr<char[]> own_stack;
};

SignalScope::SignalScope() : saved_(new Saved) {
  for (size_t i = 0; i < std::size(kOsdSignals); ++i)
    sigaction(kOsdSignals[i], nullptr, &saved_->actions[i]);
  // Faults inside OCC_CATCH_SIGNALS become OSD_Signal exceptions; floating-point traps off.
  OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
  // Segmentation faults (a stack overflow among them) are handled on a stack of their own.
  saved_->own_stack.reset(new char[kSignalStackBytes]);  // NOLINT: not zeroed
  stack_t own{};
  own.ss_sp = saved_->own_stack.get();
  own.ss_size = kSignalStackBytes;
  sigaltstack(&own, &saved_->stack);
  for (const int sig : {SIGSEGV, SIGBUS}) {
    struct sigaction a {};
    sigaction(sig, nullptr, &a);
    a.sa_flags |= SA_ONSTACK;
    sigaction(sig, &a, nullptr);
  }
}

SignalScope::~SignalScope() {
  for (size_t i = 0; i < std::size(kOsdSignals); ++i)
    sigaction(kOsdSignals[i], &saved_->actions[i], nullptr);
  sigaltstack(&saved_->stack, nullptr);
  delete saved_;
}

std::string text(const Handle(TCollection_HAsciiString) & s) {
  if (s.IsNull()) return {};
  std::string t = s->ToCString();
  const size_t a = t.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  const size_t b = t.find_last_not_of(" \t\r\n");
  return t.substr(a, b - a + 1);
}

Status read_file(XSControl_Reader& reader, const std::string& path,
                 const std::string& format_name) {
  // Geometry comes out in millimetres whatever the file's unit.
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  const IFSelect_ReturnStatus status = reader.ReadFile(path.c_str());
  if (status != IFSelect_RetDone)
    return Error{ErrorCode::kFileNotParsed,
                 {},
                 {format_name, std::int64_t{status == IFSelect_RetVoid ? 1 : 0}}};
  return ok_status();
}

void transfer_roots(XSControl_Reader& reader, Deadline& deadline,
                    const std::function<std::string(const Handle(Standard_Transient) &)>& name_of,
                    ReadOutput& out) {
  if (auto w = reader_checks(reader.WS()->ModelCheckList(), "load")) out.warnings.push_back(*w);
  reader.TransferRoots(deadline.Start());
  const Handle(Transfer_TransientProcess) process =
      reader.WS()->TransferReader()->TransientProcess();
  if (!process.IsNull())
    if (auto w = reader_checks(process->CheckList(Standard_False), "transfer"))
      out.warnings.push_back(*w);
  out.shape = reader.OneShape();
  out.shape_names = shape_names(process, name_of);
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(out.shape, TopAbs_FACE, faces);
  for (int i = 1; i <= faces.Extent(); ++i)
    if (std::string label = entity_label(reader, faces(i)); !label.empty())
      out.face_entities.emplace_back(faces(i), std::move(label));
  out.precision = file_precision(reader);
}

namespace {

// Reader messages named in a warning: the most frequent few of fails and of warnings.
constexpr std::size_t kReaderMessagesShown = 3;

// Appends to `values` the count of `messages` (by text: how often each was given), how many
// kinds there are and how many are shown, then (count, text) of the most frequent shown.
void add_messages(const std::map<std::string, int>& messages, std::vector<MessageValue>& values) {
  std::vector<std::pair<int, std::string>> v;
  std::int64_t total = 0;
  for (const auto& [msg, k] : messages) {
    v.emplace_back(-k, msg);
    total += k;
  }
  std::sort(v.begin(), v.end());
  const std::size_t shown = std::min(v.size(), kReaderMessagesShown);
  values.insert(values.end(),
                {total, static_cast<std::int64_t>(v.size()), static_cast<std::int64_t>(shown)});
  for (std::size_t i = 0; i < shown; ++i) {
    std::string msg = v[i].second;
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    values.insert(values.end(), {std::int64_t{-v[i].first}, std::move(msg)});
  }
}

}  // namespace

std::optional<Warning> reader_checks(const Interface_CheckIterator& checks,
                                     const std::string& stage) {
  std::map<std::string, int> fails, warnings;
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& c = checks.Value();
    for (int i = 1; i <= c->NbFails(); ++i) fails[c->CFail(i)]++;
    for (int i = 1; i <= c->NbWarnings(); ++i) warnings[c->CWarning(i)]++;
  }
  if (fails.empty() && warnings.empty()) return std::nullopt;
  Warning w{WarningCode::kReaderMessages, {stage}};
  add_messages(fails, w.values);
  add_messages(warnings, w.values);
  return w;
}

std::vector<std::pair<TopoDS_Shape, std::string>> shape_names(
    const Handle(Transfer_TransientProcess) & process,
    const std::function<std::string(const Handle(Standard_Transient) &)>& name_of) {
  std::vector<std::pair<TopoDS_Shape, std::string>> out;
  if (process.IsNull()) return out;
  for (int i = 1; i <= process->NbMapped(); ++i) {
    const Handle(Transfer_Binder) b = process->MapItem(i);
    if (b.IsNull() || !b->HasResult()) continue;
    const TopoDS_Shape sh = TransferBRep::ShapeResult(b);
    if (sh.IsNull() || (sh.ShapeType() != TopAbs_FACE && sh.ShapeType() != TopAbs_WIRE &&
                        sh.ShapeType() != TopAbs_EDGE))
      continue;
    std::string name = name_of(process->Mapped(i));
    if (!name.empty()) out.emplace_back(sh, std::move(name));
  }
  return out;
}

}  // namespace plyfit::importers::occt
