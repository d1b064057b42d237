// swa::dds::credentialProblem (idl/runtime/dds/include/swa/dds/security_check.h) on credentials made by
// deploy/security/make-credentials.sh in a temporary directory per test, removed afterwards: the genuine files of
// every role pass; each way of spoiling them (changed signature, widened grant, another CA, another UAV's
// permissions, another key, another CA's identity, garbage) is named with the file and the concrete cause. Pure
// OpenSSL, no DDS traffic.

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "scratch.h"
#include "swa/dds/deployment.h"
#include "swa/dds/security_check.h"

namespace swa::dds {
namespace {

namespace fs = std::filesystem;

const std::string kMakeCredentials = std::string(SWA_SOURCE_DIR) + "/deploy/security/make-credentials.sh";

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeFile(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

bool contains(const std::optional<std::string>& problem, const std::string& part) {
  return problem && problem->find(part) != std::string::npos;
}

std::string show(const std::optional<std::string>& problem) { return problem ? *problem : "(no problem found)"; }

class SecurityCheckTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "scratch");
    ASSERT_TRUE(makeCredentials(creds()));
  }

  // deploy/security/make-credentials.sh DIR 3: a CA, swa_sim, swa_monitor, swa_agent_0 .. swa_agent_2.
  bool makeCredentials(const fs::path& dir) const {
    const fs::path log = dir_ / ("make-credentials." + dir.filename().string() + ".log");
    const std::string command = "bash '" + kMakeCredentials + "' '" + dir.string() + "' 3 >'" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    EXPECT_EQ(status, 0) << command << "\n" << readFile(log);
    return status == 0;
  }

  fs::path creds() const { return dir_ / "creds"; }
  SecurityFiles files(const std::string& participant) const { return securityFiles(creds().string(), participant); }

  // `bytes` as a new file of this test, for one slot of SecurityFiles.
  std::string scratch(const std::string& name, const std::string& bytes) const {
    const fs::path p = dir_ / "scratch" / name;
    writeFile(p, bytes);
    return p.string();
  }

  std::string signatureOf(const std::string& permissions) const {
    return "signature of " + permissions + " does not verify against " + files("swa_agent_1").ca;
  }

  swa::testing::ScratchDir dir_{"swa_security_check"};  // private keys never outlive the test
};

TEST_F(SecurityCheckTest, GenuineCredentialsOfEveryRolePass) {
  // GIVEN the genuine credentials of every role
  for (const char* name : {"swa_sim", "swa_monitor", "swa_agent_0", "swa_agent_1", "swa_agent_2"}) {
    // WHEN each is checked THEN no problem is found
    const auto problem = credentialProblem(files(name));
    EXPECT_FALSE(problem.has_value()) << name << ": " << show(problem);
  }
}

// The base64 signature block of an S/MIME document made by `openssl smime -sign`: [begin, end).
std::pair<std::size_t, std::size_t> signatureBlock(const std::string& smime) {
  const std::size_t part = smime.rfind("pkcs7-signature");  // the signature part's own Content-Type
  const std::size_t begin = part == std::string::npos ? part : smime.find("\n\n", part);
  const std::size_t end = begin == std::string::npos ? begin : smime.find("\n------", begin + 2);
  if (end == std::string::npos) return {0, 0};
  return {begin + 2, end};
}

// One base64 character of the signature changed: near its start (the PKCS#7 structure, the signer's certificate)
// and near its end (the ECDSA signature value). Either way the document no longer verifies.
TEST_F(SecurityCheckTest, ChangedSignatureByteIsASignatureProblem) {
  // GIVEN UAV 1's genuine permissions and the base64 block of their signature
  const SecurityFiles genuine = files("swa_agent_1");
  const std::string original = readFile(genuine.permissions);
  const auto [begin, end] = signatureBlock(original);
  ASSERT_LT(begin + 100, end) << original;
  // WHEN one character is changed near its start or near its end, and the credentials are checked
  for (const std::size_t at : {begin + 40, end - 12}) {
    std::string tampered = original;
    ASSERT_NE(tampered[at], '\n');
    tampered[at] = tampered[at] == 'A' ? 'B' : 'A';
    SecurityFiles f = genuine;
    f.permissions = scratch("permissions_" + std::to_string(at) + ".p7s", tampered);
    const auto problem = credentialProblem(f);
    // THEN the problem found is that the signature does not verify against the CA, the file named
    EXPECT_TRUE(contains(problem, signatureOf(f.permissions))) << "byte " << at << ": " << show(problem);
  }
}

// The attack a tampered file would attempt: UAV 1's command topic widened to every UAV's, signature left as it was.
TEST_F(SecurityCheckTest, WidenedGrantIsASignatureProblem) {
  // GIVEN UAV 1's permissions with the grant swa/uav1/cmd_vel widened to swa/uav*/cmd_vel, the signature as it was
  SecurityFiles f = files("swa_agent_1");
  std::string text = readFile(f.permissions);
  const std::size_t grant = text.find("swa/uav1/cmd_vel");
  ASSERT_NE(grant, std::string::npos) << text;
  text[grant + 7] = '*';
  f.permissions = scratch("permissions.p7s", text);
  // WHEN they are checked THEN the problem found is that the signature no longer verifies
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, signatureOf(f.permissions) + " (modified after signing, or signed by another CA"))
      << show(problem);
}

// The governance is checked the same way: its discovery protection lowered from ENCRYPT to NONE.
TEST_F(SecurityCheckTest, ChangedGovernanceIsASignatureProblem) {
  // GIVEN UAV 1's credentials with the governance's discovery protection lowered from ENCRYPT to NONE
  SecurityFiles f = files("swa_agent_1");
  std::string text = readFile(f.governance);
  const std::string from = "<discovery_protection_kind>ENCRYPT<";
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, from.size(), "<discovery_protection_kind>NONE<");
  f.governance = scratch("governance.p7s", text);
  // WHEN they are checked THEN the problem found is that the governance's signature does not verify
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, "signature of " + f.governance + " does not verify against " + f.ca)) << show(problem);
}

TEST_F(SecurityCheckTest, PermissionsOfAnotherCaAreASignatureProblem) {
  // GIVEN UAV 1's credentials with the permissions of UAV 1 made by another CA
  const fs::path other = dir_ / "other_ca";
  ASSERT_TRUE(makeCredentials(other));
  SecurityFiles f = files("swa_agent_1");
  f.permissions = securityFiles(other.string(), "swa_agent_1").permissions;
  // WHEN they are checked THEN the problem found is that the permissions' signature does not verify
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, signatureOf(f.permissions))) << show(problem);
}

// Validly signed, but for another subject: UAV 2's document in UAV 1's place.
TEST_F(SecurityCheckTest, AnotherUavsPermissionsNameBothSubjects) {
  // GIVEN UAV 1's credentials with UAV 2's validly signed permissions
  SecurityFiles f = files("swa_agent_1");
  f.permissions = files("swa_agent_2").permissions;
  // WHEN they are checked THEN the problem found names both subjects, the permissions' and the certificate's
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, f.permissions + " grants subject 'CN=swa_agent_2,O=SWA' but " + f.certificate +
                                    " is 'CN=swa_agent_1,O=SWA'"))
      << show(problem);
}

TEST_F(SecurityCheckTest, AnotherIdentitysKeyIsAKeyProblem) {
  // GIVEN UAV 1's credentials with UAV 0's private key
  SecurityFiles f = files("swa_agent_1");
  f.private_key = files("swa_agent_0").private_key;
  // WHEN they are checked THEN the problem found is that the key is not the certificate's
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, f.private_key + " is not the private key of " + f.certificate)) << show(problem);
}

// An identity (certificate and its own key) issued by another CA.
TEST_F(SecurityCheckTest, CertificateOfAnotherCaIsACertificateProblem) {
  // GIVEN UAV 1's credentials with a certificate and key of another CA
  const fs::path other = dir_ / "other_ca";
  ASSERT_TRUE(makeCredentials(other));
  SecurityFiles f = files("swa_agent_1");
  const SecurityFiles foreign = securityFiles(other.string(), "swa_agent_1");
  f.certificate = foreign.certificate;
  f.private_key = foreign.private_key;
  // WHEN they are checked THEN the problem found is that the certificate does not verify against the CA
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem,
                       f.certificate + " does not verify against " + f.ca + ": unable to get local issuer certificate"))
      << show(problem);
}

// Several things wrong: the first in check order is the one named (the certificate before the permissions).
TEST_F(SecurityCheckTest, FirstProblemInCheckOrderIsNamed) {
  // GIVEN UAV 1's credentials with a certificate of another CA and UAV 0's permissions
  const fs::path other = dir_ / "other_ca";
  ASSERT_TRUE(makeCredentials(other));
  SecurityFiles f = files("swa_agent_1");
  f.certificate = securityFiles(other.string(), "swa_agent_1").certificate;
  f.permissions = files("swa_agent_0").permissions;
  // WHEN they are checked THEN the problem found is the certificate's, checked first
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, f.certificate + " does not verify against ")) << show(problem);
}

// A key under a passphrase: reported, never prompted for (a drone's service has no one at its terminal).
TEST_F(SecurityCheckTest, EncryptedKeyIsReportedWithoutPrompting) {
  // GIVEN UAV 1's credentials with its private key encrypted under a passphrase
  SecurityFiles f = files("swa_agent_1");
  const std::string encrypted = (dir_ / "scratch" / "encrypted_key.pem").string();
  const std::string command =
      "openssl pkey -in '" + f.private_key + "' -aes256 -passout pass:secret -out '" + encrypted + "' </dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  f.private_key = encrypted;
  // WHEN they are checked THEN the problem found is that the key is no readable unencrypted key, without a prompt
  const auto problem = credentialProblem(f);
  EXPECT_TRUE(contains(problem, encrypted + " holds no readable unencrypted PEM private key")) << show(problem);
}

// Every file replaced in turn by something that is not a credential: a message naming that file, no crash.
TEST_F(SecurityCheckTest, GarbageInAnyFileIsNamed) {
  // GIVEN UAV 1's genuine credentials, and kinds of garbage: empty, random bytes, text, half a file, PEM armour
  // around garbage, a missing file, a directory
  const SecurityFiles genuine = files("swa_agent_1");
  std::mt19937 random(20240521);
  std::string noise(3000, '\0');
  for (char& c : noise) c = static_cast<char>(random() & 0xff);
  struct Garbage {
    std::string what;
    std::function<std::string(const std::string& genuine_path, const std::string& slot)> make;
    std::string cause;  // after the file name; "" where only OpenSSL's parser can say what is wrong
  };
  const std::vector<Garbage> kinds{
      {"empty file", [&](const std::string&, const std::string& slot) { return scratch(slot + ".empty", ""); },
       " is empty"},
      {"random bytes", [&](const std::string&, const std::string& slot) { return scratch(slot + ".noise", noise); },
       ""},
      {"text", [&](const std::string&, const std::string& slot) { return scratch(slot + ".txt", "hello\n"); }, ""},
      {"first half of the genuine file",
       [&](const std::string& path, const std::string& slot) {
         const std::string bytes = readFile(path);
         return scratch(slot + ".half", bytes.substr(0, bytes.size() / 2));
       },
       ""},
      {"PEM armour around garbage",
       [&](const std::string&, const std::string& slot) {
         return scratch(slot + ".armour",
                        "-----BEGIN CERTIFICATE-----\nAAAA////\n-----END CERTIFICATE-----\n"
                        "-----BEGIN PRIVATE KEY-----\nAAAA////\n-----END PRIVATE KEY-----\n");
       },
       ""},
      {"missing file", [&](const std::string&, const std::string& slot) { return (dir_ / "missing" / slot).string(); },
       " cannot be opened (No such file or directory)"},
      {"directory", [&](const std::string&, const std::string&) { return (dir_ / "scratch").string(); },
       " cannot be read (Is a directory)"},
  };
  struct Slot {
    std::string name;
    std::string SecurityFiles::*field;
  };
  const std::vector<Slot> slots{{"ca", &SecurityFiles::ca},
                                {"certificate", &SecurityFiles::certificate},
                                {"private_key", &SecurityFiles::private_key},
                                {"governance", &SecurityFiles::governance},
                                {"permissions", &SecurityFiles::permissions}};
  // WHEN each of its files in turn is replaced by each kind of garbage and checked
  for (const Slot& slot : slots) {
    for (const Garbage& g : kinds) {
      SecurityFiles f = genuine;
      f.*slot.field = g.make(genuine.*slot.field, slot.name);
      const auto problem = credentialProblem(f);
      // THEN the problem found names that file, and the cause where more than OpenSSL's parser can tell it
      EXPECT_TRUE(contains(problem, f.*slot.field + g.cause)) << slot.name << ", " << g.what << ": " << show(problem);
    }
  }
}

}  // namespace
}  // namespace swa::dds
