// The real broker, /usr/sbin/mosquitto, on a free loopback port, with its
// configuration (and, as asked, a password file or a CA and a server
// certificate) in a temporary folder of its own. stop() and start() again
// give a broker restarted on the same port, as an operator's would be.
//
// Options::deployment runs it with the deployment configuration,
// resources/mosquitto/rcm.conf and rcm.acl, as they are but for the
// listeners (moved to free loopback ports: port() plain, tlsPort() TLS) and
// the files (the password file of Options::users, the certificates, the
// persistence folder, all in the temporary folder).
#pragma once

#include <QByteArray>
#include <QDir>
#include <QFile>
#include <QProcess>
#include <QStringList>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTemporaryDir>

#include <csignal>
#include <utility>
#include <pwd.h>
#include <unistd.h>

namespace rcm::test {

class MosquittoProcess {
public:
    struct Options {
        // Non-empty: anonymous clients are refused, this one is let in.
        QString user;
        QString password;
        // A TLS listener with a server certificate for 127.0.0.1, signed by
        // a CA made for the occasion (caFile()).
        bool tls = false;
        // resources/mosquitto/rcm.conf, with these users (name, password).
        bool deployment = false;
        QList<std::pair<QString, QString>> users = {};
        // More lines for the tests' own configuration ("max_queued_messages 20000").
        QStringList more = {};
    };

    MosquittoProcess() : MosquittoProcess(Options{}) {}
    explicit MosquittoProcess(const Options& options)
        : m_options(options), m_port(freePort()), m_tlsPort(options.deployment ? freePort() : 0)
    {
        QObject::connect(&m_process, &QProcess::readyReadStandardError,
                         [this] { m_stderr += m_process.readAllStandardError(); });
    }
    ~MosquittoProcess()
    {
        if (m_process.state() != QProcess::NotRunning) {
            m_process.kill();
            m_process.waitForFinished();
        }
    }
    MosquittoProcess(const MosquittoProcess&) = delete;
    MosquittoProcess& operator=(const MosquittoProcess&) = delete;

    // Writes the configuration (the first time) and starts the broker; the
    // caller then waits for accepts().
    bool start()
    {
        if (m_configPath.isEmpty() && !configure())
            return false;
        m_process.start(QStringLiteral("/usr/sbin/mosquitto"), {QStringLiteral("-c"), m_configPath});
        return m_process.waitForStarted();
    }
    // The listener takes connections: a plain TCP connection succeeds.
    bool accepts()
    {
        QTcpSocket probe;
        probe.connectToHost(QHostAddress::LocalHost, m_port);
        const bool ok = probe.waitForConnected(200);
        probe.abort();
        return ok;
    }
    // SIGTERM: the broker closes every connection and exits.
    bool stop()
    {
        ::kill(static_cast<pid_t>(m_process.processId()), SIGTERM);
        const bool done = m_process.waitForFinished(5000);
        m_stderr += m_process.readAllStandardError();
        return done;
    }
    bool isRunning() const { return m_process.state() == QProcess::Running; }

    quint16 port() const { return m_port; }
    quint16 tlsPort() const { return m_tlsPort; }
    QString caFile() const { return m_dir.filePath(QStringLiteral("ca.crt")); }
    QString dir() const { return m_dir.path(); }
    const QByteArray& stderrText() const { return m_stderr; }
    // What went wrong making the configuration or its certificates.
    const QString& setupError() const { return m_setupError; }

    static quint16 freePort()
    {
        QTcpServer probe;
        probe.listen(QHostAddress::LocalHost, 0);
        return probe.serverPort();
    }

    // Runs a program in the temporary folder; false, with setupError(), if it fails.
    bool run(const QString& program, const QStringList& arguments)
    {
        QProcess p;
        p.setWorkingDirectory(m_dir.path());
        p.start(program, arguments);
        if (!p.waitForFinished(30000) || p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0) {
            m_setupError = program + u' ' + arguments.join(u' ') + QStringLiteral(": ") +
                           QString::fromLocal8Bit(p.readAllStandardError());
            return false;
        }
        return true;
    }

private:
    bool configure()
    {
        if (m_options.deployment)
            return configureDeployment();
        QStringList conf{
            QStringLiteral("listener %1 127.0.0.1").arg(m_port),
            QStringLiteral("persistence false"),
            QStringLiteral("log_dest stderr"),
            // Run as root (in a container), the broker would become the
            // user "mosquitto" and could not read the temporary folder.
            QStringLiteral("user %1").arg(userName()),
        };
        conf << m_options.more;
        if (m_options.user.isEmpty()) {
            conf << QStringLiteral("allow_anonymous true");
        } else {
            const QString passwords = m_dir.filePath(QStringLiteral("passwords"));
            if (!run(QStringLiteral("mosquitto_passwd"),
                     {QStringLiteral("-b"), QStringLiteral("-c"), passwords, m_options.user, m_options.password}))
                return false;
            conf << QStringLiteral("allow_anonymous false") << QStringLiteral("password_file ") + passwords;
        }
        if (m_options.tls) {
            if (!makeCertificates())
                return false;
            conf << QStringLiteral("cafile ") + caFile()
                 << QStringLiteral("certfile ") + m_dir.filePath(QStringLiteral("server.crt"))
                 << QStringLiteral("keyfile ") + m_dir.filePath(QStringLiteral("server.key"));
        }
        m_configPath = m_dir.filePath(QStringLiteral("mosquitto.conf"));
        QFile f(m_configPath);
        if (!f.open(QIODevice::WriteOnly))
            return false;
        f.write(conf.join(u'\n').toUtf8() + '\n');
        return true;
    }

    // The deployment configuration, line for line, but for where it listens
    // and where its files are.
    bool configureDeployment()
    {
        QFile source(QStringLiteral(RCM_SOURCE_DIR "/resources/mosquitto/rcm.conf"));
        if (!source.open(QIODevice::ReadOnly)) {
            m_setupError = source.fileName() + QStringLiteral(": ") + source.errorString();
            return false;
        }
        const QString passwords = m_dir.filePath(QStringLiteral("passwords"));
        for (qsizetype i = 0; i < m_options.users.size(); ++i) {
            QStringList arguments{QStringLiteral("-b")};
            if (i == 0)
                arguments << QStringLiteral("-c");
            arguments << passwords << m_options.users[i].first << m_options.users[i].second;
            if (!run(QStringLiteral("mosquitto_passwd"), arguments))
                return false;
        }
        if (!makeCertificates())
            return false;
        QDir().mkpath(m_dir.filePath(QStringLiteral("db")));
        QStringList conf;
        for (const QString& line : QString::fromUtf8(source.readAll()).split(u'\n')) {
            const QString key = line.section(u' ', 0, 0);
            if (key == QLatin1String("listener"))
                conf << QStringLiteral("listener %1 127.0.0.1")
                            .arg(line.section(u' ', 1, 1) == QLatin1String("8883") ? m_tlsPort : m_port);
            else if (key == QLatin1String("password_file"))
                conf << QStringLiteral("password_file ") + passwords;
            else if (key == QLatin1String("acl_file"))
                conf << QStringLiteral("acl_file " RCM_SOURCE_DIR "/resources/mosquitto/rcm.acl");
            else if (key == QLatin1String("certfile"))
                conf << QStringLiteral("certfile ") + m_dir.filePath(QStringLiteral("server.crt"));
            else if (key == QLatin1String("keyfile"))
                conf << QStringLiteral("keyfile ") + m_dir.filePath(QStringLiteral("server.key"));
            else if (key == QLatin1String("persistence_location"))
                conf << QStringLiteral("persistence_location ") + m_dir.filePath(QStringLiteral("db")) + u'/';
            else
                conf << line;
        }
        // Before the listeners: global settings.
        conf.prepend(QStringLiteral("user %1").arg(userName()));
        conf.prepend(QStringLiteral("log_dest stderr"));
        m_configPath = m_dir.filePath(QStringLiteral("mosquitto.conf"));
        QFile f(m_configPath);
        if (!f.open(QIODevice::WriteOnly))
            return false;
        f.write(conf.join(u'\n').toUtf8() + '\n');
        return true;
    }

    // A CA, and a server certificate for IP 127.0.0.1 signed by it: P-256
    // keys, quick to make.
    bool makeCertificates()
    {
        const QString openssl = QStringLiteral("openssl");
        const QStringList ec{QStringLiteral("-newkey"), QStringLiteral("ec"), QStringLiteral("-pkeyopt"),
                             QStringLiteral("ec_paramgen_curve:prime256v1"), QStringLiteral("-nodes")};
        QFile ext(m_dir.filePath(QStringLiteral("server.ext")));
        if (!ext.open(QIODevice::WriteOnly))
            return false;
        ext.write("subjectAltName=IP:127.0.0.1\n");
        ext.close();
        return run(openssl, QStringList{QStringLiteral("req"), QStringLiteral("-x509")} + ec +
                                QStringList{QStringLiteral("-keyout"), QStringLiteral("ca.key"), QStringLiteral("-out"),
                                            QStringLiteral("ca.crt"), QStringLiteral("-days"), QStringLiteral("2"),
                                            QStringLiteral("-subj"), QStringLiteral("/CN=rcm test CA")}) &&
               run(openssl, QStringList{QStringLiteral("req")} + ec +
                                QStringList{QStringLiteral("-keyout"), QStringLiteral("server.key"),
                                            QStringLiteral("-out"), QStringLiteral("server.csr"),
                                            QStringLiteral("-subj"), QStringLiteral("/CN=127.0.0.1")}) &&
               run(openssl, {QStringLiteral("x509"), QStringLiteral("-req"), QStringLiteral("-in"),
                             QStringLiteral("server.csr"), QStringLiteral("-CA"), QStringLiteral("ca.crt"),
                             QStringLiteral("-CAkey"), QStringLiteral("ca.key"), QStringLiteral("-CAcreateserial"),
                             QStringLiteral("-out"), QStringLiteral("server.crt"), QStringLiteral("-days"),
                             QStringLiteral("2"), QStringLiteral("-extfile"), QStringLiteral("server.ext")});
    }

    static QString userName()
    {
        const passwd* pw = ::getpwuid(::getuid());
        return pw ? QString::fromLocal8Bit(pw->pw_name) : QStringLiteral("root");
    }

    Options m_options;
    quint16 m_port;
    quint16 m_tlsPort;
    QTemporaryDir m_dir;
    QString m_configPath;
    QString m_setupError;
    QProcess m_process;
    QByteArray m_stderr;
};

}  // namespace rcm::test
